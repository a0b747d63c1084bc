// vds: bake meshes into volumetric depth sprites and ask what is inside.
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>

#include <vds/atomic_file.h>
#include <vds/error.h>
#include <vds/sprite.h>

#include "cli.h"

namespace cli {

Args::Args(int argc, char** argv, const std::vector<std::string>& valued, const std::vector<std::string>& flags) {
    auto in = [](const std::vector<std::string>& list, const std::string& s) {
        for (const auto& x : list)
            if (x == s) return true;
        return false;
    };
    for (int i = 0; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.size() > 1 && a[0] == '-' && !(a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.'))) {
            if (in(valued, a)) {
                if (i + 1 >= argc) throw UsageError("option " + a + " needs a value");
                values_[a] = argv[++i];
            } else if (in(flags, a)) {
                flagsSet_[a] = true;
            } else {
                throw UsageError("unknown option " + a);
            }
        } else {
            positional_.push_back(a);
        }
    }
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
    auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

std::uint32_t Args::getUint(const std::string& name, std::uint32_t fallback) const {
    auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    const std::string& s = it->second;
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
    if (s.empty() || *end || s[0] == '-' || errno || v > 0xffffffffull)
        throw UsageError(name + " expects a whole number, not '" + s + "'");
    return std::uint32_t(v);
}

void Args::expectPositional(std::size_t n, const std::string& what) const {
    if (positional_.size() != n) throw UsageError("expected " + what);
}

std::vector<std::uint32_t> parseResolutions(const std::string& list) {
    std::vector<std::uint32_t> out;
    std::stringstream in(list);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const unsigned long v = std::strtoul(item.c_str(), &end, 10);
        if (item.empty() || *end || v == 0 || v > vds::kMaxResolution)
            throw UsageError("--resolutions expects numbers 1.." + std::to_string(vds::kMaxResolution) + ", not '" +
                             item + "'");
        out.push_back(std::uint32_t(v));
    }
    if (out.empty()) throw UsageError("--resolutions is empty");
    return out;
}

void writeTextFile(const std::string& path, const std::string& text) {
    vds::AtomicFile out(path);
    std::FILE* f = std::fopen(out.path().c_str(), "wb");
    if (!f) throw vds::IoError(path + ": cannot write");
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok) throw vds::IoError(path + ": cannot write (disk full?)");
    out.commit();
}

void progress(bool quiet, const std::string& what) {
    if (!quiet) std::fprintf(stderr, "vds: %s\n", what.c_str());
}

} // namespace cli

namespace {

const char* kUsage =
    "usage: vds <command> [options]\n"
    "\n"
    "Volumetric depth sprites: bake a closed triangle mesh once, then ask which\n"
    "points are inside it.\n"
    "\n"
    "commands:\n"
    "  bake      MESH -o OUT.vds        bake a mesh (OBJ, PLY, STL, OFF) into a sprite\n"
    "  classify  SPRITE.vds POINTS -o LABELS.txt\n"
    "                                   label points 1 inside / 0 outside\n"
    "  info      SPRITE.vds             describe a sprite file\n"
    "  eval      MESH                   accuracy of sprites vs the exact classifier\n"
    "  compare   MESH                   VDS vs slicemaps and solid voxels: error, memory, speed\n"
    "\n"
    "Run 'vds <command> --help' for a command's options.\n";

} // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? cli::kUsage : 0;
    }
    const std::string command = argv[1];
    try {
        if (command == "bake") return cli::bake(argc - 2, argv + 2);
        if (command == "classify") return cli::classify(argc - 2, argv + 2);
        if (command == "info") return cli::info(argc - 2, argv + 2);
        if (command == "eval") return cli::eval(argc - 2, argv + 2);
        if (command == "compare") return cli::compare(argc - 2, argv + 2);
        std::fprintf(stderr, "vds: unknown command '%s' (try 'vds --help')\n", command.c_str());
        return cli::kUsage;
    } catch (const cli::UsageError& e) {
        std::fprintf(stderr, "vds %s: %s (try 'vds %s --help')\n", command.c_str(), e.what(), command.c_str());
        return cli::kUsage;
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds %s: error: %s\n", command.c_str(), e.what());
        return cli::kFailure;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "vds %s: error: out of memory\n", command.c_str());
        return cli::kFailure;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds %s: error: %s\n", command.c_str(), e.what());
        return cli::kFailure;
    }
}
