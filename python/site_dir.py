"""Prints where `cmake --install` puts the package vds under an install prefix,
for the interpreter that runs this (CMake's Python3_EXECUTABLE): a folder that
interpreter searches where there is one.

    python3 python/site_dir.py PREFIX

1. PREFIX is a virtual environment (pyvenv.cfg): its site-packages.
2. One of the interpreter's site folders lies under PREFIX (Debian's python3:
   /usr/local -> lib/python3.11/dist-packages, /usr -> lib/python3/dist-packages):
   that folder, the shortest such path.
3. Otherwise the posix_prefix scheme's platlib (lib/python3.11/site-packages),
   which PYTHONPATH then names.
"""
import os
import site
import sys
import sysconfig

prefix = os.path.realpath(sys.argv[1])
scheme_vars = {"base": prefix, "platbase": prefix, "installed_base": prefix, "installed_platbase": prefix}
folder = None
if not os.path.isfile(os.path.join(prefix, "pyvenv.cfg")):
    found = []
    for candidate in site.getsitepackages():
        candidate = os.path.realpath(candidate)
        if candidate.startswith(prefix + os.sep):
            found.append(os.path.relpath(candidate, prefix))
    if found:
        folder = min(found, key=lambda path: path.count(os.sep))
if folder is None:
    scheme = "venv" if "venv" in sysconfig.get_scheme_names() else "posix_prefix"
    folder = os.path.relpath(sysconfig.get_path("platlib", scheme, vars=scheme_vars), prefix)
print(folder)
