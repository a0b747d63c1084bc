// vds: bake meshes into volumetric depth sprites and ask what is inside.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <algorithm>
#include <string>
#include <vector>

#include <vds/atomic_file.h>
#include <vds/error.h>
#include <vds/sprite.h>

#include <vds/vdb.h>

#include "cli.h"

namespace cli {

CLI::Validator wholeNumber(std::uint64_t lo, std::uint64_t hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            errno = 0;
            const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
            if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || errno == ERANGE ||
                value < lo || value > hi)
                return "expects a whole number " + std::to_string(lo) + ".." + std::to_string(hi) + ", not '" + text +
                       "'";
            text = std::to_string(value);
            return {};
        },
        "");
}

void addGridOptions(CLI::App& command, GridArgs& grid, const std::string& boxHelp) {
    command.add_option("--dims", grid.dims, "cells along each axis")
        ->transform(wholeNumber(1, vds::kMaxResolution))
        ->type_name("N");
    command.add_option("--dims-xyz", grid.dimsXyz, "cells along x, y and z")
        ->expected(3)
        ->transform(wholeNumber(1, vds::kMaxResolution))
        ->type_name("NX NY NZ");
    command.add_option("--box", grid.box, boxHelp)->expected(6)->type_name("X0 Y0 Z0 X1 Y1 Z1");
}

void requireGridSize(const GridArgs& args) {
    if ((args.dims == 0) == args.dimsXyz.empty()) throw CLI::ValidationError("give --dims N or --dims-xyz NX NY NZ");
}

vds::Box boxOf(const GridArgs& args, const vds::Box& bounds, float pad) {
    const std::vector<float>& b = args.box;
    vds::Box box = b.empty() ? bounds : vds::Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    const glm::vec3 margin = pad * (box.hi - box.lo);
    box.lo -= margin;
    box.hi += margin;
    return box;
}

vds::Grid gridOf(const GridArgs& args, const vds::Box& bounds, float pad, bool slabs) {
    requireGridSize(args);
    vds::Grid grid;
    grid.box = boxOf(args, bounds, pad);
    grid.dims = args.dims ? glm::uvec3(args.dims) : glm::uvec3(args.dimsXyz[0], args.dimsXyz[1], args.dimsXyz[2]);
    vds::checkGrid(slabs ? grid.slabX(0, 1) : grid);
    return grid;
}

CLI::Option* addMesh(CLI::App& command, std::string& path) {
    return command.add_option("MESH", path, "triangle mesh (OBJ, PLY, STL, OFF)")->required()->type_name("");
}

std::string joinChoices(const std::vector<std::string>& names) {
    std::string joined;
    for (const std::string& name : names) joined += (joined.empty() ? "" : "|") + name;
    return joined;
}

CLI::Option* addChoice(CLI::App& command, const std::string& name, std::string& value,
                       const std::vector<std::string>& names, const std::string& help) {
    const CLI::Validator member(
        [names, name](std::string& text) -> std::string {
            if (std::find(names.begin(), names.end(), text) != names.end()) return {};
            return unknownValue(name.substr(name.find_first_not_of('-')), text, names);
        },
        "");
    return command.add_option(name, value, help)->check(member)->type_name(joinChoices(names));
}

CLI::Option* addResolution(CLI::App& command, std::uint32_t& resolution, const std::string& help) {
    return command.add_option("--resolution", resolution, help)
        ->transform(wholeNumber(1, vds::kMaxResolution))
        ->type_name("1.." + std::to_string(vds::kMaxResolution));
}

CLI::Option* addResolutions(CLI::App& command, std::vector<std::uint32_t>& resolutions, std::uint32_t max) {
    return command.add_option("--resolutions", resolutions, "comma-separated, each 1.." + std::to_string(max))
        ->delimiter(',')
        ->allow_extra_args(false)
        ->transform(wholeNumber(1, max))
        ->type_name("N,N");
}

void writeTextFile(const std::string& path, const std::string& text) {
    vds::AtomicFile out(path);
    std::FILE* f = std::fopen(out.path().c_str(), "wb");
    if (!f) throw vds::IoError(path + ": cannot write");
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok) throw vds::IoError(path + ": cannot write (disk full?)");
    out.commit();
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void reportSteps(const std::function<void(const std::string&)>& progress, const char* verb, std::size_t done,
                 std::size_t total, const char* units, double seconds) {
    constexpr double kQuietSeconds = 1.0;
    if (seconds < kQuietSeconds || done == total) return;
    char line[128];
    std::snprintf(line, sizeof line, "%s %zu of %zu %s (%u%%) in %.1f s", verb, done, total, units,
                  unsigned(100.0 * double(done) / double(total)), seconds);
    progress(line);
}

std::function<void(const std::string&)> progressPrinter(bool quiet) {
    return [quiet](const std::string& what) {
        if (!quiet) std::fprintf(stderr, "vds: %s\n", what.c_str());
    };
}

void tellAboutMesh(const char* command, const std::string& name, const vds::MeshReport& report, vds::Rule rule,
                   const vds::MeshFlags& flags) {
    const std::string warning = vds::insideWarning(report, rule, flags);
    if (!warning.empty()) std::fprintf(stderr, "vds %s: warning: %s: %s\n", command, name.c_str(), warning.c_str());
    const std::string note = vds::insideNote(report, rule, flags);
    if (!note.empty()) std::fprintf(stderr, "vds %s: note: %s: %s\n", command, name.c_str(), note.c_str());
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string best = vds::nearestName(word, candidates);
    return best.empty() ? std::string() : " (did you mean '" + best + "'?)";
}

std::string unknownValue(const std::string& kind, const std::string& text, const std::vector<std::string>& names) {
    std::string expected;
    for (std::size_t k = 0; k < names.size(); ++k)
        expected += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
    return "unknown " + kind + " '" + text + "' (expected " + expected + ")" + didYouMean(text, names);
}

namespace {

// " (did you mean 'X'?)" for the arguments CLI11 did not expect: a
// misspelled subcommand, or a misspelled option of the chosen command.
std::string suggestion(const CLI::App& app, const std::vector<std::string>& unexpected) {
    const auto chosen = app.get_subcommands();
    for (const std::string& arg : unexpected) {
        std::vector<std::string> names;
        std::string word = arg;
        if (chosen.empty()) {
            for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
        } else {
            if (arg.rfind("-", 0) != 0) continue;
            word = arg.substr(0, arg.find('='));
            for (const CLI::Option* o : chosen.front()->get_options())
                for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
        }
        const std::string best = vds::nearestName(word, names);
        if (!best.empty()) return " (did you mean '" + best + "'?)";
    }
    return {};
}

} // namespace

} // namespace cli

int main(int argc, char** argv) {
    CLI::App app("Volumetric depth sprites: bake a closed triangle mesh once, then ask which points are inside it.",
                 "vds");
    app.get_formatter()->label("Usage", "usage");
    app.get_formatter()->column_width(36);
    app.option_defaults()->always_capture_default();
    app.set_version_flag("--version", "vds " + vds::vdsVersion() + " (" + vds::vdbLibrary() +
                                          (vds::vdbAvailable() ? ": writes .vdb)" : ": .vdb output refused)"));
    cli::addBake(app);
    cli::addClassify(app);
    cli::addInfo(app);
    cli::addEval(app);
    cli::addCompare(app);
    cli::addVoxelize(app);
    cli::addDistance(app);
    cli::addSdf(app);
    app.add_subcommand("help", "print this help")->callback([&app] {
        std::fputs(app.get_formatter()->make_help(&app, "vds", CLI::AppFormatMode::Normal).c_str(), stdout);
    });
    app.require_subcommand(1);
    app.allow_extras(); // a word that is no command gets its nearest command suggested below
    app.footer("Run 'vds <command> --help' for a command's options.");
    if (argc < 2) {
        std::fputs(app.help().c_str(), stderr);
        return 2;
    }
    // The command whose callback runs, or which the error is about.
    const auto who = [&app] {
        const auto chosen = app.get_subcommands();
        return chosen.empty() ? std::string("vds") : "vds " + chosen.front()->get_name();
    };
    try {
        app.parse(argc, argv);
        if (!app.remaining().empty()) {
            std::fprintf(stderr, "vds: '%s' is not a vds command%s (try 'vds --help')\n", app.remaining().front().c_str(),
                         cli::suggestion(app, app.remaining()).c_str());
            return 2;
        }
        return 0;
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        if (app.get_subcommands().empty() && argv[1][0] != '-') {
            std::fprintf(stderr, "vds: '%s' is not a vds command%s (try 'vds --help')\n", argv[1],
                         cli::suggestion(app, {argv[1]}).c_str());
            return 2;
        }
        std::string hint;
        if (dynamic_cast<const CLI::ExtrasError*>(&e) || dynamic_cast<const CLI::RequiredError*>(&e)) {
            std::vector<std::string> args(argv + 1, argv + argc);
            hint = cli::suggestion(app, args);
        }
        std::fprintf(stderr, "%s: %s%s (try '%s --help')\n", who().c_str(), e.what(), hint.c_str(), who().c_str());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: error: out of memory\n", who().c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", who().c_str(), e.what());
        return 1;
    }
}
