// The sylva command-line program: dispatches to the sub-commands.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "Commands.h"

namespace {

void printUsage(std::FILE* stream) {
    std::fputs(
        "usage: sylva COMMAND [options]\n"
        "\n"
        "commands:\n"
        "  render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl egl|osmesa|glfw] [-D "
        "name=value]\n"
        "                 render the project's views to images\n"
        "  jobs PROJECT [--json] [--out DIR]\n"
        "                 list the series' jobs (indices, groups, outputs, cost, current)\n"
        "  assemble PROJECT [--out DIR]\n"
        "                 comparisons, videos and contact sheets from finished images (no GL)\n"
        "  cache stats|prune|clear [--disk-cache DIR] [--budget-mb N] [--json]\n"
        "                 inspect or trim the disk tile cache\n"
        "  watch PROJECT [--views NAME] [--camera NAME] [--out DIR] [--size WxH] [--exit-after N]\n"
        "                 re-render on every change of the project or its data (headless)\n"
        "  view PROJECT [--scenario S] [--camera C] [--size WxH] [--budget-ms N] [--script FILE]\n"
        "               [--gl glfw|egl|osmesa]\n"
        "                 the interactive viewer: fly, walk, save cameras, hot reload\n"
        "  check PROJECT [-D name=value] [--set block.attr=value] [--print-params] [--lenient]\n"
        "                [--diagnostics=text|json]\n"
        "                 report every problem in a project without rendering\n"
        "  analyse PROJECT [--only NAME] [--out DIR] [--json] [-D name=value]\n"
        "                 compute the project's ztv blocks and write their GeoTIFFs\n"
        "  montage PROJECT [--only NAME] [--out DIR] [--json] [-D name=value]\n"
        "                 photomontages and wirelines of the project's photo blocks\n"
        "  fmt [--check] FILES...\n"
        "                 rewrite project files in canonical layout (--check: only report)\n"
        "  dump --json PROJECT [-D name=value] [--set block.attr=value]\n"
        "                 print the evaluated model of every scenario as JSON\n"
        "  doc [KIND] [--markdown] [--update FILE]\n"
        "                 the language reference from the schema registry\n"
        "  plant generate --preset NAME --seed N [--leaves N] -o MODEL.gltf|.glb\n"
        "                 a procedural tree (oak, conifer, birch, bush, palm) as glTF\n"
        "  plant montage [--seed N] [--leaves N] [--size WxH] [--billboards] -o IMAGE.png\n"
        "                 the presets side by side (software rasterizer)\n"
        "  plant build (IN | --synthetic LEAVES) -o OUT.plod [--threads N]\n"
        "                 build the ellipsoid/line LoD of a plant\n"
        "  plant info FILE\n"
        "                 a .plod: levels, primitive counts, errors and bytes; a model\n"
        "                 (.gltf, .glb, .obj): import it and summarise it\n"
        "  bench SUITE [--json]\n"
        "                 run a benchmark suite (sylva bench --help lists them)\n"
        "\n"
        "environment:\n"
        "  SYLVA_GL=egl|osmesa|glfw   OpenGL back end (default: EGL, falling back to OSMesa)\n"
        "  SYLVA_SHADER_DIR=DIR       read shaders from DIR instead of the built-in copies\n",
        stream);
}

}  // namespace

int main(int argc, char** argv) {
#if defined(__GLIBC__)
    // Tiles (>= 270 KB each) then always come from mmap, so the memory of a tile the
    // Scheduler's cache evicts returns to the system at once. glibc's adaptive
    // threshold would otherwise raise itself to the tile size after the first free and
    // serve tiles from per-thread arenas, which fragment and keep the peak resident
    // (measured by `sylva bench tiles`: peak 1.56x the cache budget, 1.16x with this).
    mallopt(M_MMAP_THRESHOLD, 256 * 1024);
#endif
    if (argc < 2) {
        printUsage(stderr);
        return 2;
    }
    const std::string command = argv[1];
    const std::vector<std::string> arguments(argv + 2, argv + argc);
    if (command == "render") {
        return sylva::app::runRender(arguments);
    }
    if (command == "jobs") {
        return sylva::app::runJobs(arguments);
    }
    if (command == "assemble") {
        return sylva::app::runAssemble(arguments);
    }
    if (command == "cache") {
        return sylva::app::runCache(arguments);
    }
    if (command == "watch") {
        return sylva::app::runWatch(arguments);
    }
    if (command == "view") {
        return sylva::app::runView(arguments);
    }
    if (command == "check") {
        return sylva::app::runCheck(arguments);
    }
    if (command == "analyse") {
        return sylva::app::runAnalyse(arguments);
    }
    if (command == "montage") {
        return sylva::app::runMontage(arguments);
    }
    if (command == "fmt") {
        return sylva::app::runFmt(arguments);
    }
    if (command == "dump") {
        return sylva::app::runDump(arguments);
    }
    if (command == "doc") {
        return sylva::app::runDoc(arguments);
    }
    if (command == "plant") {
        // Plant sub-commands: LoD build and .plod info here, the rest (generate,
        // montage, model info) in PlantCommand.cpp.
        const std::string sub = arguments.empty() ? "" : arguments[0];
        const std::vector<std::string> rest(arguments.begin() + (arguments.empty() ? 0 : 1),
                                            arguments.end());
        if (sub == "build") {
            return sylva::app::runPlantBuild(rest);
        }
        if (sub == "info" && rest.size() == 1 && rest[0].size() > 5 &&
            rest[0].compare(rest[0].size() - 5, 5, ".plod") == 0) {
            return sylva::app::runPlantInfo(rest);
        }
        return sylva::app::runPlant(arguments);
    }
    if (command == "bench") {
        return sylva::app::runBench(arguments);
    }
    if (command == "--help" || command == "-h" || command == "help") {
        printUsage(stdout);
        return 0;
    }
    if (command == "--version") {
        std::puts("sylva 0.1.0");
        return 0;
    }
    std::fprintf(stderr, "sylva: unknown command '%s'\n", command.c_str());
    printUsage(stderr);
    return 2;
}
