"""Every LCM type has the same fingerprint in Python and in C++."""
import subprocess

import pytest

import contactsim
from contactsim import _lcmtypes

from conftest import BUILD

TOOL = BUILD / "bin" / "contactsim-lcm-fingerprints"


def cpp_fingerprints():
    if not TOOL.exists():
        pytest.skip("%s is not built (run `make`)" % TOOL)
    out = subprocess.run([str(TOOL)], capture_output=True, text=True, timeout=30, check=True).stdout
    table = {}
    for line in out.splitlines():
        if line.strip():
            name, fp = line.split()
            table[name] = fp.lower()
    return table


def test_python_and_cpp_fingerprints_agree():
    cpp = cpp_fingerprints()
    assert sorted(cpp) == sorted(_lcmtypes.TYPE_NAMES)
    for name in _lcmtypes.TYPE_NAMES:
        cls = getattr(contactsim, name)
        py = cls._get_packed_fingerprint().hex()
        assert py == cpp[name], "%s: python %s, C++ %s" % (name, py, cpp[name])
        assert int(cpp[name], 16) == cls._get_hash_recursive([])
