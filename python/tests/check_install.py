"""The package vds installed two ways, each imported outside the source and
build trees by an interpreter that is given no PYTHONPATH:

1. pip install --no-index --no-build-isolation SOURCE, into a fresh virtual
   environment (--system-site-packages: Debian's numpy), through the in-tree
   backend python/build_backend.py: a CMake build of its own in BUILD_DIR;
2. cmake --install CMAKE_BUILD --component python --prefix VENV, into a second
   fresh virtual environment (python/site_dir.py chooses its site-packages).

Each one classifies points against a cube built here: the exact classifier
and a CPU-baked sprite both agree with |p|_inf < 1.

    python3 check_install.py SOURCE CMAKE_BUILD BUILD_DIR
Not collected by pytest (ctest runs it as Python.Install).
"""
import os
import shutil
import subprocess
import sys
import tempfile

CHECK = r"""
import os, sys
import numpy as np
import vds
where = os.path.realpath(vds.__file__)
assert where.startswith(os.path.realpath(sys.prefix) + os.sep), (where, sys.prefix)
V = np.array([[x, y, z] for x in (-1.0, 1.0) for y in (-1.0, 1.0) for z in (-1.0, 1.0)])
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
F = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.int32)
points = np.array([[0, 0, 0], [0.5, -0.9, 0.3], [1.5, 0, 0], [0, 0, -3], [0.99, 0.99, 0.99], [-1.2, 0.1, 0.1]])
expected = np.abs(points).max(axis=1) < 1
exact = vds.Classifier(V, F, "exact").classify(points)
assert (exact == expected).all(), exact
sprite = vds.bake(V, F, resolution=64, method="cpu")
assert (sprite.contains(points) == expected).all()
print("vds from", where, ":", int(expected.sum()), "of", len(points), "points inside, as expected")
"""


def run(command, **kwargs):
    print("+ " + " ".join(command), flush=True)
    subprocess.run(command, check=True, **kwargs)


def main():
    source, cmake_build, build_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    # No PYTHONPATH (ctest's Python tests set one to the build tree), no user site.
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(PYTHONNOUSERSITE="1", PIP_DISABLE_PIP_VERSION_CHECK="1", PIP_NO_INPUT="1")
    work = tempfile.mkdtemp(prefix="vds-install-")
    try:
        pip_env = os.path.join(work, "pip-venv")
        run([sys.executable, "-m", "venv", "--system-site-packages", pip_env], env=env)
        python = os.path.join(pip_env, "bin", "python")
        if subprocess.run([python, "-m", "pip", "--version"], env=env, capture_output=True).returncode != 0:
            sys.exit("check_install: the virtual environment has no pip (Debian: python3-venv and python3-pip)")
        run([python, "-m", "pip", "install", "--no-index", "--no-cache-dir", "--no-build-isolation",
             "--config-settings", "build-dir=" + build_dir, source], env=env, cwd=work)
        run([python, "-c", CHECK], env=env, cwd=work)

        cmake_env = os.path.join(work, "cmake-venv")
        run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", cmake_env], env=env)
        run(["cmake", "--install", cmake_build, "--component", "python", "--prefix", cmake_env], env=env)
        run([os.path.join(cmake_env, "bin", "python"), "-c", CHECK], env=env, cwd=work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
