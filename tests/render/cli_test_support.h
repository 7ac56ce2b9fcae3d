#pragma once
// Runs the `penumbra` binary as a user would and captures its exit code, stdout and stderr.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace penumbra::test {

struct CliResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

inline std::string readWholeFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// `arguments` is passed through the shell: quote paths with spaces yourself. `environment` is a
// prefix such as "VK_ICD_FILENAMES=/nonexistent".
inline CliResult runCli(const std::string& arguments, const std::string& environment = "") {
    const auto dir = std::filesystem::temp_directory_path() / ("penumbra_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto outPath = dir / "stdout.txt", errPath = dir / "stderr.txt";
    const std::string command = environment + " " + PENUMBRA_CLI_PATH + " " + arguments + " >" + outPath.string() +
                                " 2>" + errPath.string();
    const int status = std::system(command.c_str());
    CliResult result;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = readWholeFile(outPath);
    result.err = readWholeFile(errPath);
    return result;
}

inline int lineCount(const std::string& text) {
    int lines = 0;
    for (char c : text) lines += c == '\n';
    return lines + (!text.empty() && text.back() != '\n');
}

}  // namespace penumbra::test
