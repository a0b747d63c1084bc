// The vds command-line tool: shared argument handling. Only main() and the
// command functions turn errors into exit codes and one-line messages.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {

/// Exit codes: 0 success, 1 the work failed (bad file, bad mesh, no GL...),
/// 2 the command line is wrong.
constexpr int kFailure = 1;
constexpr int kUsage = 2;

/// A command-line mistake; main prints it with the usage hint and exits 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Parsed arguments: options that take a value, flags, and positionals.
class Args {
public:
    /// `valued` lists options that take a value ("-o", "--resolution"),
    /// `flags` those that do not ("--gpu"). Anything else starting with '-'
    /// is a UsageError.
    Args(int argc, char** argv, const std::vector<std::string>& valued, const std::vector<std::string>& flags);

    bool has(const std::string& name) const { return values_.count(name) || flagsSet_.count(name); }
    std::string get(const std::string& name, const std::string& fallback = "") const;
    std::uint32_t getUint(const std::string& name, std::uint32_t fallback) const;
    const std::vector<std::string>& positional() const { return positional_; }
    /// Throws UsageError unless there are exactly `n` positionals, naming them.
    void expectPositional(std::size_t n, const std::string& what) const;

private:
    std::map<std::string, std::string> values_;
    std::map<std::string, bool> flagsSet_;
    std::vector<std::string> positional_;
};

/// Parses "256,512,1024": each 1..vds::kMaxResolution; throws UsageError.
std::vector<std::uint32_t> parseResolutions(const std::string& list);

/// Writes `text` to `path` whole or not at all (vds::AtomicFile); throws vds::IoError.
void writeTextFile(const std::string& path, const std::string& text);

/// Prints "vds: <what>" progress lines to stderr unless quiet.
void progress(bool quiet, const std::string& what);

int bake(int argc, char** argv);
int classify(int argc, char** argv);
int info(int argc, char** argv);
int eval(int argc, char** argv);
int compare(int argc, char** argv);

} // namespace cli
