"""Puts the generated LCM message modules into the wheel.

Everything else is declared in pyproject.toml. A wheel (or a regular,
non-editable ``pip install``) runs lcm-gen on ``lcmtypes/*.lcm`` and ships
the modules as ``contactsim/_generated/<type>.py``, where ``_lcmtypes`` finds
them; the generated code is never committed. An editable install keeps
reading them from the build folder, as the repository's own tests do.

lcm-gen is taken from ``$LCM_GEN``, else the ``lcm`` wheel (a build
requirement, which ships lcm-gen), else the one on PATH (Debian's
liblcm-bin). The .lcm files are ``$CONTACTSIM_LCMTYPES_DIR``, else the
repository's ``lcmtypes/`` two folders up.
"""
import glob
import os
import shutil
import subprocess
import sys
import tempfile

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))


def lcmtypes_dir():
    folder = os.environ.get("CONTACTSIM_LCMTYPES_DIR") or os.path.join(HERE, "..", "..", "lcmtypes")
    if not glob.glob(os.path.join(folder, "*.lcm")):
        raise RuntimeError("contactsim: no .lcm files in %s; build the wheel from the repository "
                           "(pip wheel clients/python) or set CONTACTSIM_LCMTYPES_DIR" % folder)
    return os.path.abspath(folder)


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
        print("contactsim: %d generated LCM modules in %s" % (len(modules), target))


setup(cmdclass={"build_py": BuildPyWithLcmTypes})
