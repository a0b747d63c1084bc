"""The PEP 517 build backend of the Python package vds (pyproject.toml names it).

    pip install --no-build-isolation .      # from the repository root
    pip install .                           # the same: the backend asks for nothing to install

It uses Debian's own tools and nothing from the network: CMake configures the
repository with the tests, tools, samples and benchmarks off, builds the one
target the package needs (the extension vds._vds and the libraries under it),
installs the CMake component ``python`` into a staging folder and packs that
folder into a wheel for the interpreter that runs this backend (whose numpy
headers the extension is built against: the build uses the interpreter's own
site packages even under pip's build isolation, since numpy cannot be fetched).

The CMake build folder is kept between builds (a rebuild compiles only what
changed): ``build-wheel/`` in the source tree, or another one named with
``pip install -C build-dir=PATH .`` (``--config-settings``). The environment
variables CMake reads apply (CMAKE_GENERATOR, CMAKE_BUILD_PARALLEL_LEVEL,
CMAKE_CXX_COMPILER_LAUNCHER for ccache); Ninja is used where it is installed.
"""
import base64
import hashlib
import io
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import zipfile

try:
    import tomllib
except ImportError:  # Python < 3.11: the few keys read here, by hand
    tomllib = None

_SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class BuildError(RuntimeError):
    """A step of the build failed; the message says which and how to fix it."""


def _project():
    """The [project] table of pyproject.toml, its version checked against CMake's."""
    with open(os.path.join(_SOURCE, "pyproject.toml"), "rb") as f:
        text = f.read()
    if tomllib is not None:
        project = tomllib.loads(text.decode())["project"]
    else:
        table = text.decode().split("[project]", 1)[1]
        project = {key: value for key, value in re.findall(r'^([a-z-]+)\s*=\s*"([^"]*)"', table, re.M)}
        project["dependencies"] = re.findall(r'"([^"]+)"', re.search(r"^dependencies\s*=\s*\[(.*?)\]", table,
                                                                   re.M | re.S).group(1))
    with open(os.path.join(_SOURCE, "CMakeLists.txt"), encoding="utf-8") as f:
        match = re.search(r"project\(\s*vds\s+VERSION\s+([0-9.]+)", f.read())
    if match is None or match.group(1) != project["version"]:
        raise BuildError("vds: pyproject.toml's version %s differs from CMakeLists.txt's project(vds VERSION %s): "
                         "make them one" % (project["version"], match.group(1) if match else "?"))
    return project


def _metadata(project):
    lines = ["Metadata-Version: 2.1", "Name: " + project["name"], "Version: " + project["version"],
             "Summary: " + project.get("description", "")]
    if "requires-python" in project:
        lines.append("Requires-Python: " + project["requires-python"])
    for dependency in project.get("dependencies", []):
        lines.append("Requires-Dist: " + dependency)
    if "license" in project and "text" in project["license"]:
        lines.append("License: " + project["license"]["text"])
    return "\n".join(lines) + "\n"


def _tag():
    """The wheel tag of this interpreter: cp311-cp311-linux_x86_64."""
    if sys.implementation.name != "cpython":
        raise BuildError("vds: the extension is built for CPython only, not " + sys.implementation.name)
    version = "cp%d%d" % sys.version_info[:2]
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return "%s-%s%s-%s" % (version, version, sys.abiflags, platform)


def _clean_environment():
    """This environment without pip's build isolation, so that CMake's Python
    finds the interpreter's own numpy (headers it builds against)."""
    env = dict(os.environ)
    for name in ("PYTHONPATH", "PYTHONNOUSERSITE", "PYTHONHOME"):
        env.pop(name, None)
    return env


def _run(command, what):
    print("vds: " + " ".join(command), flush=True)
    try:
        # Output goes to stderr: pip shows it with -v, and on failure.
        subprocess.run(command, check=True, env=_clean_environment(), stdout=sys.stderr)
    except FileNotFoundError:
        raise BuildError("vds: %s needs %s, which is not installed (tools/install-deps.sh installs it)"
                         % (what, command[0])) from None
    except subprocess.CalledProcessError as error:
        raise BuildError("vds: %s failed (exit %d): see the output above" % (what, error.returncode)) from None


def _build_dir(config_settings):
    folder = (config_settings or {}).get("build-dir") or os.path.join(_SOURCE, "build-wheel")
    return os.path.abspath(folder)


def _build_package(build, stage):
    """Configures and builds the extension in `build`, installs the package into stage/vds."""
    cmake = shutil.which("cmake")
    if cmake is None:
        raise BuildError("vds: building the extension needs cmake, which is not on PATH "
                         "(tools/install-deps.sh installs it)")
    configure = [cmake, "-S", _SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                 "-DVDS_BUILD_TESTS=OFF", "-DVDS_BUILD_TOOLS=OFF", "-DVDS_BUILD_SAMPLES=OFF",
                 "-DVDS_BUILD_BENCHMARKS=OFF", "-DVDS_PYTHON=ON", "-DVDS_PYTHON_REQUIRED=ON",
                 "-DVDS_PYTHON_INSTALL_DIR=.", "-DPython3_EXECUTABLE=" + sys.executable]
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")) and "CMAKE_GENERATOR" not in os.environ \
            and shutil.which("ninja"):
        configure += ["-G", "Ninja"]
    _run(configure, "configuring the extension")
    _run([cmake, "--build", build, "--target", "vds_python"], "building the extension")
    _run([cmake, "--install", build, "--component", "python", "--prefix", stage], "staging the package")
    if not os.path.isfile(os.path.join(stage, "vds", "__init__.py")):
        raise BuildError("vds: the CMake install of component python left no vds/__init__.py in " + stage)


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (name, digest, len(data))


def _dist_info_files(project, tag):
    return {
        "METADATA": _metadata(project).encode(),
        "WHEEL": ("Wheel-Version: 1.0\nGenerator: vds build_backend\nRoot-Is-Purelib: false\nTag: %s\n"
                  % tag).encode(),
    }


# The PEP 517 hooks.

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    project = _project()
    dist_info = "%s-%s.dist-info" % (project["name"], project["version"])
    os.makedirs(os.path.join(metadata_directory, dist_info), exist_ok=True)
    for name, data in _dist_info_files(project, _tag()).items():
        with open(os.path.join(metadata_directory, dist_info, name), "wb") as f:
            f.write(data)
    return dist_info


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    project = _project()
    tag = _tag()
    name = "%s-%s-%s.whl" % (project["name"], project["version"], tag)
    dist_info = "%s-%s.dist-info" % (project["name"], project["version"])
    with tempfile.TemporaryDirectory(prefix="vds-wheel-") as stage:
        _build_package(_build_dir(config_settings), stage)
        files = []
        for folder, subfolders, names in os.walk(os.path.join(stage, "vds")):
            subfolders[:] = sorted(d for d in subfolders if d != "__pycache__")
            for file_name in sorted(names):
                path = os.path.join(folder, file_name)
                files.append((os.path.relpath(path, stage).replace(os.sep, "/"), path))
        # Written to a temporary name and renamed: no half wheel is left on failure.
        target = os.path.join(wheel_directory, name)
        partial = target + ".part"
        record = []
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as wheel:
            for arcname, path in files:
                with open(path, "rb") as f:
                    data = f.read()
                info = zipfile.ZipInfo(arcname, date_time=(1980, 1, 1, 0, 0, 0))
                info.external_attr = (os.stat(path).st_mode & 0o777 | 0o100000) << 16
                info.compress_type = zipfile.ZIP_DEFLATED
                wheel.writestr(info, data)
                record.append(_record_line(arcname, data))
            for file_name, data in _dist_info_files(project, tag).items():
                arcname = dist_info + "/" + file_name
                wheel.writestr(zipfile.ZipInfo(arcname, date_time=(1980, 1, 1, 0, 0, 0)), data)
                record.append(_record_line(arcname, data))
            record.append(dist_info + "/RECORD,,")
            wheel.writestr(zipfile.ZipInfo(dist_info + "/RECORD", date_time=(1980, 1, 1, 0, 0, 0)),
                           ("\n".join(record) + "\n").encode())
        os.replace(partial, target)
    return name


def build_sdist(sdist_directory, config_settings=None):
    """The files git tracks (or, outside a git checkout, the source tree less build folders)."""
    project = _project()
    base = "%s-%s" % (project["name"], project["version"])
    try:
        listed = subprocess.run(["git", "-C", _SOURCE, "ls-files", "-z"], check=True,
                                capture_output=True).stdout.decode().split("\0")
        paths = [p for p in listed if p and os.path.isfile(os.path.join(_SOURCE, p))]
    except (OSError, subprocess.CalledProcessError):
        paths = []
        for folder, subfolders, names in os.walk(_SOURCE):
            subfolders[:] = [d for d in subfolders if not (d.startswith(".") or d.startswith("build")
                                                           or d == "__pycache__")]
            paths += [os.path.relpath(os.path.join(folder, n), _SOURCE) for n in names]
    name = base + ".tar.gz"
    target = os.path.join(sdist_directory, name)
    with tarfile.open(target + ".part", "w:gz") as sdist:
        for path in sorted(paths):
            sdist.add(os.path.join(_SOURCE, path), arcname=base + "/" + path, recursive=False)
        pkg_info = _metadata(project).encode()
        info = tarfile.TarInfo(base + "/PKG-INFO")
        info.size = len(pkg_info)
        sdist.addfile(info, io.BytesIO(pkg_info))
    os.replace(target + ".part", target)
    return name
