#pragma once
// Runs the penumbra program (PENUMBRA_CLI_PATH), or another of the project's programs, as a user would and captures its exit code, stdout
// and stderr, for the CLI tests.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace penumbra::test {

struct CliRun {
    int exitCode = -1;  // -1 when the process did not exit normally (e.g. a crash)
    std::string out;
    std::string err;
};

// Runs `program` with `arguments` appended as-is (quote paths with spaces yourself); `environment` is
// a prefix such as "VK_DRIVER_FILES=/nonexistent.json" (or a wrapper such as "xvfb-run -a").
inline CliRun runProgram(const std::string& program, const std::string& arguments, const std::string& environment = "") {
    static int counter = 0;
    const std::string errPath = (std::filesystem::temp_directory_path() /
                                 ("penumbra_cli_err_" + std::to_string(::getpid()) + "_" + std::to_string(counter++)))
                                    .string();
    const std::string command = environment + " " + program + " " + arguments + " 2>" + errPath;
    CliRun run;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return run;
    char buffer[4096];
    size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) run.out.append(buffer, n);
    const int status = ::pclose(pipe);
    if (WIFEXITED(status)) run.exitCode = WEXITSTATUS(status);
    std::ifstream errFile(errPath);
    std::stringstream err;
    err << errFile.rdbuf();
    run.err = err.str();
    std::filesystem::remove(errPath);
    return run;
}

// `name` in a folder of its own for this test process (PREFIX_PID, made if missing): ctest runs tests
// in parallel processes, and two of them writing one file fail each other.
inline std::filesystem::path processTempPath(const std::string& prefix, const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir / name;
}

inline CliRun runPenumbra(const std::string& arguments, const std::string& environment = "") {
    return runProgram(PENUMBRA_CLI_PATH, arguments, environment);
}

// A one-line user error: exactly one line on stderr, starting with "penumbra: ".
inline bool isOneLineError(const std::string& err) {
    return err.rfind("penumbra: ", 0) == 0 && err.find('\n') == err.size() - 1;
}

// A user error: exit code 1 and exactly one line on stderr, starting with "penumbra: ", that
// mentions `mentions`.
inline void expectOneLineError(const CliRun& result, const std::string& mentions) {
    EXPECT_EQ(result.exitCode, 1) << result.err;
    EXPECT_TRUE(isOneLineError(result.err)) << result.err;
    EXPECT_NE(result.err.find(mentions), std::string::npos) << result.err;
}

}  // namespace penumbra::test
