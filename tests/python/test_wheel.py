"""The client's wheel works outside the repository (docs/packaging.md).

Builds the wheel from a copy of clients/python (so that the tree is left as
it was), installs it into a new virtual environment in tmp, and drives a
real server from there: ``import contactsim`` with the wheel's own generated
LCM types, ``contactsim-py`` and the lockstep ``Controller``. The new
environment reaches the dependencies (lcm, numpy, ...) through a .pth file
pointing at this interpreter's site-packages, so nothing is downloaded.

Also: an sdist carries the .lcm files, so that a wheel built from it alone,
offline and far from the repository, has its generated types.
"""
import os
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import textwrap
from pathlib import Path

import pytest

from conftest import REPO

BUILD_TIMEOUT = 120  # lcm-gen and setuptools on two busy cores; ~10 s when idle


def _run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=kw.pop("timeout", 60), **kw)
    assert r.returncode == 0, "%s\n%s\n%s" % (" ".join(map(str, cmd)), r.stdout[-3000:], r.stderr[-3000:])
    return r


def _clean_env():
    """No hint of the repository: the installed wheel must find everything itself."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("CONTACTSIM_BUILD_DIR", "PYTHONPATH", "VIRTUAL_ENV")}
    return env


def _venv_with_test_deps(root):
    """A new venv whose only extra packages are this interpreter's, through a .pth file."""
    _run([sys.executable, "-m", "venv", str(root)], timeout=BUILD_TIMEOUT)
    py = root / "bin" / "python"
    site = _run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"]).stdout.strip()
    # the dependencies, not the repository's editable contactsim: a plain path
    # line, so the .pth files there (the editable finder among them) do not run
    Path(site, "contactsim-test-deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    return py


@pytest.fixture(scope="module")
def venv(tmp_path_factory):
    """A venv outside the repository with the wheel installed; its bin folder."""
    tmp = tmp_path_factory.mktemp("wheel")
    src = tmp / "src"
    shutil.copytree(REPO / "clients" / "python", src,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "node_modules",
                                                  "_generated"))
    env = dict(_clean_env(), CONTACTSIM_LCMTYPES_DIR=str(REPO / "lcmtypes"))
    _run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "--no-build-isolation",
          "-w", str(tmp / "dist"), str(src)], env=env, cwd=str(tmp), timeout=BUILD_TIMEOUT)
    wheels = list((tmp / "dist").glob("contactsim-*.whl"))
    assert len(wheels) == 1, wheels

    venv = tmp / "venv"
    py = _venv_with_test_deps(venv)
    _run([str(py), "-m", "pip", "install", "-q", "--no-deps", "--no-index", "--ignore-installed",
          str(wheels[0])], env=_clean_env(), cwd=str(tmp), timeout=BUILD_TIMEOUT)
    return venv / "bin"


def test_wheel_carries_its_generated_types(venv, tmp_path):
    r = _run([str(venv / "python"), "-c", textwrap.dedent("""
        import contactsim
        from contactsim import _lcmtypes
        print(contactsim.__file__)
        print(_lcmtypes.generated_dir())
        print(contactsim.state_t.__module__, len(contactsim.state_t._get_packed_fingerprint()))
        """)], env=_clean_env(), cwd=str(tmp_path))
    package, generated, state = r.stdout.split("\n")[:3]
    venv_root = str(venv.parent)
    assert package.startswith(venv_root) and generated.startswith(venv_root)
    assert generated.endswith(os.path.join("contactsim", "_generated"))
    assert state == "contactsim.state_t 8"


def test_installed_cli_and_controller_drive_a_real_server(venv, tmp_path, launch):
    server = launch()
    ends = ["--lcm-url", server.url, "--prefix", server.prefix]
    env = _clean_env()
    r = _run([str(venv / "contactsim-py"), *ends, "add", "box", "0.1", "0.1", "0.1",
              "--position", "0", "0", "1", "--mass", "2"], env=env, cwd=str(tmp_path))
    box = int(r.stdout.strip())
    _run([str(venv / "contactsim-py"), *ends, "step", "3"], env=env, cwd=str(tmp_path))
    # a controller in the installed package holds the box against gravity in lockstep
    script = textwrap.dedent("""
        import sys, contactsim
        url, prefix, box = sys.argv[1], sys.argv[2], int(sys.argv[3])
        with contactsim.Client(url=url, prefix=prefix, timeout=5) as c:
            c.wait_for_server(timeout=15)
            with contactsim.Controller(c, lambda s: {box: (0.0, 0.0, 2 * 9.81)}) as ctl:
                c.set_mode("lockstep")
                c.resume()
                ctl.wait_for_step(20, timeout=20)
                c.pause()
            print(c.state().bodies[box].linear_velocity[2])
        """)
    r = _run([str(venv / "python"), "-c", script, server.url, server.prefix, str(box)],
             env=env, cwd=str(tmp_path))
    # fell for the 3 free steps, then held: the velocity of those 3 steps only
    assert float(r.stdout.strip()) == pytest.approx(-9.81 * 3 / 240, rel=1e-6)
    status = _run([str(venv / "contactsim-py"), *ends, "status"], env=env, cwd=str(tmp_path)).stdout
    assert "lockstep" in status


def test_wheel_from_sdist_builds_offline_and_decodes(tmp_path):
    """Verifies that the sdist carries lcmtypes/*.lcm and that pip builds a
    wheel from the sdist alone (no index, no CONTACTSIM_LCMTYPES_DIR, no
    repository above it) whose installed package decodes a message with its
    own generated classes."""
    src = tmp_path / "src"
    shutil.copytree(REPO / "clients" / "python", src,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "node_modules",
                                                  "_generated"))
    # the copy is out of the repository: only the env tells the sdist where the .lcm files are
    env = dict(_clean_env(), CONTACTSIM_LCMTYPES_DIR=str(REPO / "lcmtypes"))
    sdist = _run([sys.executable, "-c", "import setuptools.build_meta as b; print(b.build_sdist('../sdist'))"],
                 env=env, cwd=str(src), timeout=BUILD_TIMEOUT).stdout.strip().splitlines()[-1]
    sdist = tmp_path / "sdist" / sdist
    with tarfile.open(sdist) as tar:
        carried = sorted(Path(n).name for n in tar.getnames() if n.endswith(".lcm"))
    assert carried == sorted(p.name for p in (REPO / "lcmtypes").glob("*.lcm"))

    shutil.rmtree(src)  # nothing but the sdist is left to build from
    env = _clean_env()
    env.pop("CONTACTSIM_LCMTYPES_DIR", None)
    _run([sys.executable, "-m", "pip", "wheel", "-q", "--no-index", "--no-deps", "--no-build-isolation",
          "-w", str(tmp_path / "dist"), str(sdist)], env=env, cwd=str(tmp_path), timeout=BUILD_TIMEOUT)
    wheels = list((tmp_path / "dist").glob("contactsim-*.whl"))
    assert len(wheels) == 1, wheels

    py = _venv_with_test_deps(tmp_path / "venv")
    _run([str(py), "-m", "pip", "install", "-q", "--no-deps", "--no-index", "--ignore-installed",
          str(wheels[0])], env=env, cwd=str(tmp_path), timeout=BUILD_TIMEOUT)
    r = _run([str(py), "-c", textwrap.dedent("""
        import contactsim
        from contactsim import _lcmtypes
        m = contactsim.state_t()
        m.time, m.step, m.state_hash = 0.25, 60, 1234
        b = contactsim.body_state_t()
        b.id, b.position, b.orientation = 7, [1.0, 2.0, 3.0], [1.0, 0.0, 0.0, 0.0]
        m.bodies, m.num_bodies = [b], 1
        s = contactsim.State(contactsim.state_t.decode(m.encode()))
        print(_lcmtypes.generated_dir())
        print(s.step, s.state_hash, s.bodies[7].position.tolist())
        """)], env=env, cwd=str(tmp_path))
    generated, decoded = r.stdout.strip().splitlines()[-2:]
    assert generated.startswith(str(tmp_path / "venv"))
    assert decoded == "60 1234 [1.0, 2.0, 3.0]"
