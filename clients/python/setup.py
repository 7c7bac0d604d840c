"""Puts the generated LCM message modules and the protocol's table into the wheel.

Everything else is declared in pyproject.toml. A wheel (or a regular,
non-editable ``pip install``) runs lcm-gen on ``lcmtypes/*.lcm`` and ships
the modules as ``contactsim/_generated/<type>.py``, with a copy of
``lcmtypes/protocol.toml`` beside them, where ``_lcmtypes`` and ``protocol``
find them; the generated code is never committed. An editable install keeps
reading them from the build folder, as the repository's own tests do.

lcm-gen is taken from ``$LCM_GEN``, else the ``lcm`` wheel (a build
requirement, which ships lcm-gen), else the one on PATH (Debian's
liblcm-bin). The .lcm files and the table are ``$CONTACTSIM_LCMTYPES_DIR``,
else an sdist's own ``lcmtypes/`` (the sdist command copies them in, since a
MANIFEST.in cannot reach above this folder), else the repository's
``lcmtypes/`` two folders up (docs/packaging.md, "Python sdist").
"""
import glob
import os
import shutil
import subprocess
import sys
import tempfile

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.command.sdist import sdist

HERE = os.path.dirname(os.path.abspath(__file__))
PROTOCOL_TABLE = "protocol.toml"  # contactsim/_lcmtypes.py reads it under this name


def protocol_files(folder):
    """The files that declare the protocol: the .lcm types and the table."""
    return sorted(glob.glob(os.path.join(folder, "*.lcm"))) + [os.path.join(folder, PROTOCOL_TABLE)]


def lcmtypes_dir():
    if os.environ.get("CONTACTSIM_LCMTYPES_DIR"):
        candidates = [os.environ["CONTACTSIM_LCMTYPES_DIR"]]
    else:
        candidates = [os.path.join(HERE, "lcmtypes"), os.path.join(HERE, "..", "..", "lcmtypes")]
    for folder in candidates:
        if glob.glob(os.path.join(folder, "*.lcm")) and os.path.isfile(os.path.join(folder, PROTOCOL_TABLE)):
            return os.path.abspath(folder)
    raise RuntimeError("contactsim: no .lcm files and %s in %s; build the wheel from the repository "
                       "(pip wheel clients/python), from an sdist, or set CONTACTSIM_LCMTYPES_DIR"
                       % (PROTOCOL_TABLE, " or ".join(candidates)))


def lcm_gen_command():
    if os.environ.get("LCM_GEN"):
        return [os.environ["LCM_GEN"]]
    try:
        import lcm  # noqa: F401  the lcm wheel runs its bundled lcm-gen through run_gen
        if hasattr(lcm, "run_gen"):
            return [sys.executable, "-c", "import lcm; lcm.run_gen()"]
    except ImportError:
        pass
    found = shutil.which("lcm-gen")
    if not found:
        raise RuntimeError("contactsim: lcm-gen not found: pip install lcm, apt install liblcm-bin, "
                           "or set LCM_GEN")
    return [found]


class BuildPyWithLcmTypes(build_py):
    """build_py, plus the generated message modules in contactsim/_generated."""

    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return  # an editable install reads the build folder's (see _lcmtypes)
        target = os.path.join(self.build_lib, "contactsim", "_generated")
        self.generate(target)

    def generate(self, target):
        lcm_files = sorted(glob.glob(os.path.join(lcmtypes_dir(), "*.lcm")))
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run(lcm_gen_command() + ["--python", "--ppath", tmp] + lcm_files, check=True)
            modules = [m for m in glob.glob(os.path.join(tmp, "contactsim", "*.py"))
                       if os.path.basename(m) != "__init__.py"]  # the package's own __init__ stays
            os.makedirs(target, exist_ok=True)
            for m in modules:
                shutil.copy(m, target)
        shutil.copy(os.path.join(lcmtypes_dir(), PROTOCOL_TABLE), target)
        print("contactsim: %d generated LCM modules and %s in %s" % (len(modules), PROTOCOL_TABLE, target))


class SdistWithLcmTypes(sdist):
    """sdist, plus the .lcm files and the table in lcmtypes/, so a wheel builds from it anywhere."""

    def make_release_tree(self, base_dir, files):
        super().make_release_tree(base_dir, files)
        target = os.path.join(base_dir, "lcmtypes")
        os.makedirs(target, exist_ok=True)
        for f in protocol_files(lcmtypes_dir()):
            shutil.copy(f, target)


setup(cmdclass={"build_py": BuildPyWithLcmTypes, "sdist": SdistWithLcmTypes})
