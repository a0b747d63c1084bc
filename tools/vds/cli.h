// The vds command-line tool. Each command (cmd_*.cpp) adds a CLI11
// subcommand whose options are bound straight into the library's option
// structs, and runs from the subcommand's callback. main() turns errors into
// exit codes and one-line messages: 0 done, 1 the work failed (a vds::Error:
// bad file, bad mesh, no GL...), 2 the command line is wrong (a CLI::ParseError).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/distance.h>
#include <vds/enum_names.h>
#include <vds/error.h>
#include <vds/grid.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>

namespace cli {

/// A whole number in [lo, hi], in decimal digits (CLI11 alone would take
/// -1 as the largest number, and 0x10 and 010 as hexadecimal and octal).
CLI::Validator wholeNumber(std::uint64_t lo, std::uint64_t hi);

/// Adds the subcommand `name`: `summary` is its line in `vds --help`,
/// `details` closes its own help. Its options are bound into a fresh `Args`
/// that lives as long as `app`, `--quiet` (no progress messages) into
/// `Args::quiet`; after parsing, its callback runs `run(args)`.
template <class Args> std::pair<CLI::App*, Args*> addCommand(CLI::App& app, const std::string& name,
                                                             const std::string& summary, const std::string& details,
                                                             void (*run)(Args&)) {
    auto args = std::make_shared<Args>();
    CLI::App* command = app.add_subcommand(name, summary);
    command->footer(details);
    command->add_flag("--quiet", args->quiet, "no progress messages");
    command->callback([args, run] { run(*args); });
    return {command, args.get()};
}

/// The MESH positional: a closed triangle mesh file.
CLI::Option* addMesh(CLI::App& command, std::string& path);

/// A grid's cells as the grid commands take them: --dims N or --dims-xyz NX
/// NY NZ, and --box instead of the input's bounds.
struct GridArgs {
    std::uint32_t dims = 0;
    std::vector<std::uint32_t> dimsXyz;
    std::vector<float> box;
};
/// Adds --dims, --dims-xyz and --box (`boxHelp` says what it replaces).
void addGridOptions(CLI::App& command, GridArgs& grid, const std::string& boxHelp);
/// Refuses neither or both of --dims and --dims-xyz (before any work).
void requireGridSize(const GridArgs& args);
/// The box a grid command covers: `bounds` (or --box) grown by `pad` of
/// its size on every side.
vds::Box boxOf(const GridArgs& args, const vds::Box& bounds, float pad = 0.0f);
/// The grid asked for over `bounds` (or --box), grown by `pad` of its size on
/// every side; refuses neither or both of --dims and --dims-xyz, and a grid
/// `vds::checkGrid` refuses. `slabs`: the grid is filled and written a slab of
/// x layers at a time, never held whole, so one x layer is what is checked
/// (a 4096^3 grid passes; its cells need only disk).
vds::Grid gridOf(const GridArgs& args, const vds::Box& bounds, float pad = 0.0f, bool slabs = false);

/// "a|b|c": the choices, for the help.
std::string joinChoices(const std::vector<std::string>& names);

/// `--name` taking one of `names` as text.
CLI::Option* addChoice(CLI::App& command, const std::string& name, std::string& value,
                       const std::vector<std::string>& names, const std::string& help);

/// " (did you mean 'X'?)" for the candidate nearest `word` where it is near
/// enough to be a typo (at most a third of its letters off), else "".
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

/// The one message for a value of an option that is none of `names`:
/// "unknown KIND 'exakt' (expected a, b or c) (did you mean 'exact'?)".
std::string unknownValue(const std::string& kind, const std::string& text, const std::vector<std::string>& names);

/// `--name` choosing a value of `E` by `names` (default: every name in
/// `EnumNames<E>`); the help lists them and shows the current value as the
/// default; an unknown name is told with the nearest one.
template <class E>
CLI::Option* addEnum(CLI::App& command, const std::string& name, E& value, const std::string& help,
                     const std::vector<std::string>& names = vds::enumNames<E>()) {
    // A name becomes the enum's number, which CLI11 then stores in `value`.
    const CLI::Validator byName(
        [names](std::string& text) -> std::string {
            if (std::find(names.begin(), names.end(), text) == names.end())
                return unknownValue(vds::EnumNames<E>::kind, text, names);
            text = std::to_string(unsigned(vds::parseEnum<E>(text)));
            return {};
        },
        "");
    return command.add_option(name, value, help)
        ->transform(byName)
        ->type_name(joinChoices(names))
        ->default_str(vds::enumName(value));
}

/// `--resolution N`, 1..vds::kMaxResolution.
CLI::Option* addResolution(CLI::App& command, std::uint32_t& resolution, const std::string& help);
/// `--resolutions N,N,...`, each 1..max.
CLI::Option* addResolutions(CLI::App& command, std::vector<std::uint32_t>& resolutions,
                            std::uint32_t max = vds::kMaxResolution);
/// `--name N`, a whole number.
template <class T>
CLI::Option* addCount(CLI::App& command, const std::string& name, T& value, const std::string& help) {
    return command.add_option(name, value, help)
        ->transform(wholeNumber(0, std::numeric_limits<T>::max()))
        ->type_name("N");
}

/// Writes `text` to `path` whole or not at all (vds::AtomicFile); throws vds::IoError.
void writeTextFile(const std::string& path, const std::string& text);

/// Prints "vds: <what>" progress lines to stderr, unless quiet.
std::function<void(const std::string&)> progressPrinter(bool quiet);

/// Seconds since `start`.
double secondsSince(std::chrono::steady_clock::time_point start);

/// "vds: labelled 32 of 256 x layers (12%) in 1.3 s" (`verb`, `done` of
/// `total` `units`): a line per step of a long run once it has run past a
/// second (a quick one says nothing, and neither does its last step).
void reportSteps(const std::function<void(const std::string&)>& progress, const char* verb, std::size_t done,
                 std::size_t total, const char* units, double seconds);

/// How this tool spells the flags the library's mesh messages name
/// (<vds/mesh_check.h>): the generalized winding number's rule; `--allow-open`
/// only where the command has it.
inline vds::MeshFlags meshFlags(bool allowOpen = false) {
    return {"--rule generalized-winding", allowOpen ? "--allow-open" : ""};
}

/// What the library says of a mesh asked by `rule` (<vds/mesh_check.h>), on
/// stderr: "vds COMMAND: warning: NAME: ..." where `rule` does not define its
/// inside or it is mis-oriented, "vds COMMAND: note: NAME: ..." of
/// non-manifold edges around a defined inside.
void tellAboutMesh(const char* command, const std::string& name, const vds::MeshReport& report, vds::Rule rule,
                   const vds::MeshFlags& flags);

void addBake(CLI::App& app);
void addClassify(CLI::App& app);
void addInfo(CLI::App& app);
void addEval(CLI::App& app);
void addCompare(CLI::App& app);
void addVoxelize(CLI::App& app);
void addDistance(CLI::App& app);
/// What `vds distance`, `vds sdf` and `vds voxelize` refuse, as classify does: an unusable or
/// flat mesh, and one whose inside `rule` does not define unless `allowOpen`;
/// then tells of it as `tellAboutMesh` does.
void checkSignedMesh(const vds::TriangleMesh& mesh, const std::string& name, vds::Rule rule, bool allowOpen,
                     const char* command);
/// The signed distance of every cell of `grid` into `cells`, as
/// `query.grid` gives it, a slab of x layers at a time (the same cells,
/// `Grid::slabX`) so that a run past a second reports progress; a
/// propagated grid in one call (it spreads across the whole grid).
void fillDistanceGrid(const vds::SignedDistance& query, const vds::Grid& grid, float* cells,
                      const vds::DistanceGridOptions& options, const std::function<void(const std::string&)>& progress);
void addSdf(CLI::App& app);

} // namespace cli
