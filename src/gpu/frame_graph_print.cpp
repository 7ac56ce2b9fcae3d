// The recorded passes of a frame as Mermaid or Graphviz dot (penumbra graph).
#include <map>
#include <sstream>

#include "core/error.h"
#include "gpu/frame_graph.h"

namespace penumbra::gpu {

namespace {

std::string quoted(const std::string& text) {
    std::string out;
    for (char c : text) out += c == '"' ? '\'' : c;
    return out;
}

struct Edge {
    size_t from = 0, to = 0;
    std::string label;
};

// An edge from the pass that last wrote each resource to every later pass that uses it; one edge per
// pair of passes, its label the resources joined by ", " (in order of first use).
std::vector<Edge> dependencies(const FrameGraph& graph) {
    const std::vector<PassRecord>& passes = graph.passes();
    std::map<std::pair<uint32_t, bool>, size_t> lastWriter;
    std::vector<Edge> edges;
    std::map<std::pair<size_t, size_t>, size_t> edgeOf;
    for (size_t p = 0; p < passes.size(); ++p) {
        for (const ResourceUse& use : passes[p].uses) {
            const auto key = std::make_pair(use.resource.id, use.resource.texture);
            if (const auto writer = lastWriter.find(key); writer != lastWriter.end() && writer->second != p) {
                const auto [found, added] = edgeOf.try_emplace({writer->second, p}, edges.size());
                if (added) edges.push_back({writer->second, p, ""});
                Edge& edge = edges[found->second];
                edge.label += (edge.label.empty() ? "" : ", ") + graph.name(use.resource);
            }
        }
        // After the edges: a pass that reads and writes a resource depends on the earlier writer.
        for (const ResourceUse& use : passes[p].uses) {
            bool writes = false;
            for (const ResourceUse& u : passes[p].uses)
                writes = writes || (u.resource == use.resource && isWrite(u.usage));
            if (writes) lastWriter[{use.resource.id, use.resource.texture}] = p;
        }
    }
    return edges;
}

std::string nodeLabel(const PassRecord& pass) {
    const size_t n = pass.barriers.size();
    return quoted(pass.name) + (n ? " (" + std::to_string(n) + (n == 1 ? " barrier)" : " barriers)") : "");
}

}  // namespace

std::string printFrameGraph(const FrameGraph& graph, const std::string& format) {
    if (format != "mermaid" && format != "dot") throw Error("unknown graph format '" + format + "' (mermaid or dot)");
    const std::vector<PassRecord>& passes = graph.passes();
    const std::vector<Edge> edges = dependencies(graph);
    std::ostringstream out;
    if (format == "mermaid") {
        out << "flowchart TD\n";
        for (size_t p = 0; p < passes.size(); ++p) out << "  p" << p << "[\"" << nodeLabel(passes[p]) << "\"]\n";
        for (const Edge& e : edges) out << "  p" << e.from << " -->|\"" << quoted(e.label) << "\"| p" << e.to << "\n";
    } else {
        out << "digraph frame {\n  rankdir=TB;\n  node [shape=box];\n";
        for (size_t p = 0; p < passes.size(); ++p) out << "  p" << p << " [label=\"" << nodeLabel(passes[p]) << "\"];\n";
        for (const Edge& e : edges) out << "  p" << e.from << " -> p" << e.to << " [label=\"" << quoted(e.label) << "\"];\n";
        out << "}\n";
    }
    return out.str();
}

}  // namespace penumbra::gpu
