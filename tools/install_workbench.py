#!/usr/bin/env python3
"""Installs the workbench where FreeCAD 0.20 reads user workbenches
($HOME/.local/share/FreeCAD/Mod/Contacts) with the built extension beside it,
and a `contacts` command-line wrapper."""
import argparse
import glob
import os
import shutil
import stat
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORKBENCH_FILES = ["Init.py", "InitGui.py", "package.xml", "README.md"]
WORKBENCH_DIRS = ["contactwb", "Resources"]


def install(build_dir, mod_dir, bin_dir):
    extensions = glob.glob(os.path.join(build_dir, "python", "contactcore*.so"))
    if not extensions:
        sys.exit(f"error: no contactcore extension in {build_dir}/python: build first (make build)")
    if os.path.isdir(mod_dir):
        shutil.rmtree(mod_dir)
    os.makedirs(mod_dir)
    for name in WORKBENCH_FILES:
        shutil.copy2(os.path.join(REPO, name), mod_dir)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for name in WORKBENCH_DIRS:
        shutil.copytree(os.path.join(REPO, name), os.path.join(mod_dir, name), ignore=ignore)
    for extension in extensions:
        shutil.copy2(extension, mod_dir)
    os.makedirs(bin_dir, exist_ok=True)
    wrapper = os.path.join(bin_dir, "contacts")
    with open(wrapper, "w") as out:
        out.write("#!/bin/sh\n"
                  "# Contacts workbench command-line tool (installed by make install)\n"
                  f'PYTHONPATH="{mod_dir}${{PYTHONPATH:+:$PYTHONPATH}}" '
                  f'exec /usr/bin/python3 -m contactwb.cli "$@"\n')
    os.chmod(wrapper, os.stat(wrapper).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    print(f"Installed the Contacts workbench in {mod_dir}")
    print(f"Installed the command-line tool {wrapper}")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--build-dir", default=os.path.join(REPO, "build"))
    parser.add_argument("--mod-dir", default=os.path.expanduser("~/.local/share/FreeCAD/Mod/Contacts"))
    parser.add_argument("--bin-dir", default=os.path.expanduser("~/.local/bin"))
    args = parser.parse_args()
    install(os.path.abspath(args.build_dir), os.path.abspath(args.mod_dir), os.path.abspath(args.bin_dir))


if __name__ == "__main__":
    main()
