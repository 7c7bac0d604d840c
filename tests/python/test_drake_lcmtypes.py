"""Drake's arm-driver messages (lcmtypes/drake/) are Drake's on the wire.

The fingerprints below are those of Drake's own generated classes, taken from
the PyPI wheel ``drake`` 1.51.1. To regenerate one (n = each key of
DRAKE_FINGERPRINTS), in a venv of its own, since the wheel and its
dependencies take about 400 MB::

    python -m venv /tmp/drakevenv && /tmp/drakevenv/bin/pip install drake
    /tmp/drakevenv/bin/python -c "import importlib; n = 'lcmt_iiwa_status'; print('0x%016x' %
        int.from_bytes(getattr(importlib.import_module('drake.' + n), n)._get_packed_fingerprint(), 'big'))"

The C++ side is tests/server/drake_lcmtypes_test.cpp, run with
CONTACTSIM_DRAKE_SAMPLE_DIR so that it writes its encoded samples; the sample
values follow the rule stated there. ``test_live_against_pydrake`` runs only
where the wheel is importable and decodes the C++ bytes with Drake's classes.
"""
import importlib
import importlib.util
import os
import shutil
import subprocess

import pytest

from conftest import BUILD, REPO
from lcm_wire import LCMTYPES, _schema

DRAKE_FINGERPRINTS = {
    "lcmt_iiwa_command": 0xddc7c7738c815334,
    "lcmt_iiwa_status": 0xf16fb804284abca3,
    "lcmt_panda_command": 0xe68df777004d59d0,
    "lcmt_panda_status": 0x19571cdf4d82fae6,
    "lcmt_schunk_wsg_command": 0x4553bc1bff499216,
    "lcmt_schunk_wsg_status": 0xec6aee3fc5ae4612,
}
GENERATED = BUILD / "lcmtypes" / "python" / "drake"
SERVER_TESTS = BUILD / "bin" / "server_tests"
JOINTS = 7
EMPTY_COUNTS = {"num_joint_velocity"}  # lcmt_panda_command sends no velocities
STRUCTS = _schema.parse_folder(LCMTYPES / "drake")


def generated_class(name):
    """The build's class, loaded from its file under a private module name:
    ``drake`` may be Drake's own package in this interpreter."""
    path = GENERATED / (name + ".py")
    if not path.exists():
        pytest.skip("%s is not generated (cmake --build build --target contactsim_lcmtypes_gen)" % path)
    spec = importlib.util.spec_from_file_location("contactsim_drake_lcmt." + name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return getattr(module, name)


def sample(cls):
    """A message of cls holding the sample values (the rule in drake_lcmtypes_test.cpp)."""
    msg = cls()
    for k, (typename, field, dims) in enumerate(STRUCTS[cls.__name__].fields):
        if dims:
            n = getattr(msg, dims[0])
            value = [k + j / 8.0 for j in range(n)]
        elif field.startswith("num_"):
            value = 0 if field in EMPTY_COUNTS else JOINTS
        elif typename == "double":
            value = k + 0.5
        elif typename == "int64_t":
            value = 1000 * (k + 1)
        else:
            assert typename == "int8_t", (cls.__name__, field)
            value = k
        setattr(msg, field, value)
    return msg


@pytest.fixture(scope="module")
def cpp_bytes(tmp_path_factory):
    """{type name: bytes} that the C++ classes encode for the samples."""
    if not SERVER_TESTS.exists():
        pytest.skip("%s is not built" % SERVER_TESTS)
    folder = tmp_path_factory.mktemp("drake_samples")
    subprocess.run([str(SERVER_TESTS), "--gtest_filter=DrakeLcmtypesTest.*"], check=True, capture_output=True,
                   timeout=60, env=dict(os.environ, CONTACTSIM_DRAKE_SAMPLE_DIR=str(folder)))
    return {name: (folder / (name + ".bin")).read_bytes() for name in DRAKE_FINGERPRINTS}


def test_every_drake_type_is_recorded():
    assert sorted(STRUCTS) == sorted(DRAKE_FINGERPRINTS)
    assert all(s.package == "drake" for s in STRUCTS.values())


@pytest.mark.parametrize("name", sorted(DRAKE_FINGERPRINTS))
def test_python_fingerprint_is_drakes(name):
    got = int.from_bytes(generated_class(name)._get_packed_fingerprint(), "big")
    assert got == DRAKE_FINGERPRINTS[name], "%s: 0x%016x" % (name, got)


@pytest.mark.parametrize("name", sorted(DRAKE_FINGERPRINTS))
def test_cpp_encoding_is_drakes_and_pythons(name, cpp_bytes):
    """The C++ bytes lead with Drake's fingerprint, decode in Python to the
    sample values and equal Python's encoding of them, byte for byte."""
    cls = generated_class(name)
    data = cpp_bytes[name]
    assert int.from_bytes(data[:8], "big") == DRAKE_FINGERPRINTS[name]
    expected = sample(cls)
    decoded = cls.decode(data)
    for field in cls.__slots__:
        assert getattr(decoded, field) == pytest.approx(getattr(expected, field)), field
    assert expected.encode() == data


def test_lcm_spy_jar_decodes_every_drake_type(cpp_bytes, tmp_path):
    """lcm-spy's type lookup (tests/java/DecodeLog.java) finds Drake's classes
    in the build's jar and decodes a log of the C++ samples."""
    jar = BUILD / "lcmtypes" / "contactsim_lcmtypes.jar"
    if not shutil.which("javac") or not jar.exists():
        pytest.skip("no JDK or no %s (cmake/lcmtypes_java.cmake)" % jar)
    import lcm
    log = lcm.EventLog(str(tmp_path / "drake.lcmlog"), "w", overwrite=True)
    for i, (name, data) in enumerate(sorted(cpp_bytes.items())):
        log.write_event(1000 * i, name.upper(), data)
    log.close()
    classpath = "/usr/share/java/lcm.jar:%s" % jar
    subprocess.run(["javac", "-nowarn", "-cp", classpath, "-d", str(tmp_path),
                    str(REPO / "tests" / "java" / "DecodeLog.java")], check=True, timeout=60)
    r = subprocess.run(["java", "-cp", "%s:%s" % (classpath, tmp_path), "DecodeLog", str(tmp_path / "drake.lcmlog")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stdout + r.stderr
    wanted = {name.upper(): "drake." + name for name in DRAKE_FINGERPRINTS}
    decoded = {line.split()[0]: line.split()[1] for line in r.stdout.splitlines() if line.split()[0] in wanted}
    assert decoded == wanted


@pytest.mark.parametrize("name", sorted(DRAKE_FINGERPRINTS))
def test_live_against_pydrake(name, cpp_bytes):
    """Drake's own class has the recorded fingerprint and reads the C++ bytes."""
    pytest.importorskip("pydrake", reason="the PyPI wheel drake is not installed (docs/protocol.md)")
    drake_cls = getattr(importlib.import_module("drake." + name), name)
    assert int.from_bytes(drake_cls._get_packed_fingerprint(), "big") == DRAKE_FINGERPRINTS[name]
    assert drake_cls.decode(cpp_bytes[name]).encode() == cpp_bytes[name]
