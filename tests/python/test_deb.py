"""The Debian package (`make package`, docs/packaging.md "Debian package"),
checked the cheap way that CI can run without root or a container.

cpack builds the .deb from the build folder into tmp (build/ is left as it
was); the tests read its file list and control fields, run its maintainer
scripts with stand-ins for the commands that would change this machine,
and unpack it with ``dpkg -x`` to start the packaged server from there on
the packaged config and scene, driven by the Python client and the packaged
contactsim-ctl. The real install, upgrade, remove and purge in a throwaway
Debian root is `make package-check` (scripts/package_check.sh).
"""
import os
import re
import shutil
import signal
import subprocess
import zipfile
from pathlib import Path

import pytest

import contactsim
from conftest import BUILD, REPO, unique_endpoint

CPACK_TIMEOUT = 300  # strips ~400 MB of RelWithDebInfo programs, on two busy cores
START_TIMEOUT = 15.0

pytestmark = pytest.mark.skipif(not (shutil.which("cpack") and shutil.which("dpkg-deb")),
                                reason="needs cpack and dpkg-deb")


def _run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=kw.pop("timeout", 60), **kw)
    assert r.returncode == 0, "%s\n%s\n%s" % (" ".join(map(str, cmd)), r.stdout[-3000:], r.stderr[-3000:])
    return r


@pytest.fixture(scope="module")
def deb(tmp_path_factory):
    """The .deb that `make package` makes, built by cpack from BUILD into tmp."""
    if not (BUILD / "CPackConfig.cmake").exists() or not (BUILD / "bin" / "contactsim-server").exists():
        pytest.skip("%s is not built (run `make`)" % BUILD)
    if "CONTACTSIM_SANITIZE:BOOL=ON" in (BUILD / "CMakeCache.txt").read_text():
        pytest.skip("the package is made from the plain build, not the sanitizer one")
    out = tmp_path_factory.mktemp("deb")
    _run(["cpack", "-G", "DEB", "--config", str(BUILD / "CPackConfig.cmake"), "-B", str(out)],
         cwd=str(BUILD), timeout=CPACK_TIMEOUT)
    debs = list(out.glob("contactsim_*.deb"))
    assert len(debs) == 1, debs
    return debs[0]


@pytest.fixture(scope="module")
def root(deb, tmp_path_factory):
    """The package's files unpacked (dpkg -x) into a folder."""
    root = tmp_path_factory.mktemp("root")
    _run(["dpkg-deb", "-x", str(deb), str(root)])
    return root


def _control(deb):
    fields = {}
    for line in _run(["dpkg-deb", "-f", str(deb)]).stdout.splitlines():
        key, _, value = line.partition(":")
        if value:
            fields[key] = value.strip()
    return fields


def test_package_holds_programs_client_config_unit_and_jar(deb):
    """Verifies the package's file list: the four programs, the C++ client
    (library, headers, generated headers, CMake config, pkg-config), the
    config under /etc, the scenes, the systemd unit and the lcm-spy jar;
    and that nothing lies outside /usr and /etc (the journal folder in
    /var/lib belongs to no package, so remove keeps it)."""
    listing = _run(["dpkg-deb", "-c", str(deb)]).stdout
    files = {line.split()[-1].lstrip(".") for line in listing.splitlines() if not line.startswith("d")}
    expected = {
        "/usr/bin/contactsim-server", "/usr/bin/contactsim-ctl", "/usr/bin/contactsim-bench",
        "/usr/bin/contactsim-bench-lockstep",
        "/usr/lib/libcontactsim_client.a", "/usr/include/contactsim/client.h",
        "/usr/include/contactsim/state_t.hpp", "/usr/lib/cmake/contactsim/contactsimConfig.cmake",
        "/usr/lib/pkgconfig/contactsim.pc",
        "/etc/contactsim/server.pbtxt", "/usr/share/contactsim/scenes/default.pbtxt",
        "/usr/lib/systemd/system/contactsim.service", "/usr/share/java/contactsim_lcmtypes.jar",
    }
    assert expected <= files, sorted(expected - files)
    outside = sorted(f for f in files if not f.startswith(("/usr/", "/etc/")))
    assert outside == []


def test_control_names_runtime_libraries_conffile_and_scripts(deb, tmp_path):
    """Verifies the control data: dpkg-shlibdeps found the runtime libraries
    (LCM, protobuf, libsodium), the config is a conffile, and the three
    maintainer scripts are there and executable."""
    fields = _control(deb)
    assert fields["Package"] == "contactsim" and fields["Architecture"] == "amd64"
    assert re.fullmatch(r"\d+\.\d+\.\d+", fields["Version"])
    depends = [d.split()[0] for d in fields["Depends"].split(", ")]
    assert "adduser" in depends
    for lib in ("liblcm1", "libsodium23", "libc6"):
        assert lib in depends, fields["Depends"]
    assert any(d.startswith("libprotobuf") for d in depends), fields["Depends"]
    _run(["dpkg-deb", "-e", str(deb), str(tmp_path / "DEBIAN")])
    control = tmp_path / "DEBIAN"
    assert (control / "conffiles").read_text().split() == ["/etc/contactsim/server.pbtxt"]
    for script in ("postinst", "prerm", "postrm"):
        assert os.access(control / script, os.X_OK), script


def _run_script(control, script, args, tmp_path, user_exists):
    """Runs a maintainer script with stand-ins for every command that would
    change this machine; returns the commands it ran, one per line."""
    shims = tmp_path / "shims"
    shims.mkdir(exist_ok=True)
    calls = tmp_path / "calls"
    calls.write_text("")
    for name in ("adduser", "install", "rm", "systemctl", "deluser"):
        (shims / name).write_text('#!/bin/sh\necho "%s $*" >> "%s"\n' % (name, calls))
        (shims / name).chmod(0o755)
    (shims / "getent").write_text("#!/bin/sh\nexit %d\n" % (0 if user_exists else 2))
    (shims / "getent").chmod(0o755)
    env = dict(os.environ, PATH="%s:/usr/bin:/bin" % shims)
    _run(["sh", str(control / script), *args], env=env)
    return calls.read_text().splitlines()


def test_maintainer_scripts_keep_the_journal_until_purge(deb, tmp_path):
    """Verifies what the maintainer scripts do: postinst configure makes the
    system user only when it is missing and the state folder for it; postrm
    deletes /var/lib/contactsim on purge and on nothing else."""
    _run(["dpkg-deb", "-e", str(deb), str(tmp_path / "DEBIAN")])
    control = tmp_path / "DEBIAN"
    first = _run_script(control, "postinst", ["configure", ""], tmp_path, user_exists=False)
    assert any(c.startswith("adduser --system --group") and c.endswith("contactsim") for c in first), first
    assert "install -d -o contactsim -g contactsim -m 0755 /var/lib/contactsim" in first
    again = _run_script(control, "postinst", ["configure", "0.1.0"], tmp_path, user_exists=True)
    assert not any(c.startswith("adduser") for c in again), again
    for action in (["remove"], ["upgrade", "0.1.0"], ["disappear"]):
        calls = _run_script(control, "postrm", action, tmp_path, user_exists=True)
        assert not any(c.startswith("rm") for c in calls), (action, calls)
    purge = _run_script(control, "postrm", ["purge"], tmp_path, user_exists=True)
    assert "rm -rf /var/lib/contactsim" in purge
    assert not any(c.startswith("deluser") for c in purge)


def test_packaged_config_names_a_packaged_scene(root):
    """Verifies that /etc/contactsim/server.pbtxt names its scene by the
    absolute path the package installs it at (relative, it would be looked
    for in /etc/contactsim/scenes)."""
    config = (root / "etc/contactsim/server.pbtxt").read_text()
    scene = re.search(r'^scene: "([^"]+)"', config, re.M).group(1)
    assert scene == "/usr/share/contactsim/scenes/default.pbtxt"
    assert (root / scene.lstrip("/")).is_file()


def test_packaged_jar_and_pkg_config_are_usable(root):
    """Verifies that the jar holds the message classes lcm-spy looks up and
    that the packaged contactsim.pc is relocatable (points into the root it
    was unpacked in)."""
    with zipfile.ZipFile(root / "usr/share/java/contactsim_lcmtypes.jar") as jar:
        assert "contactsim/state_t.class" in jar.namelist()
    if not shutil.which("pkg-config"):
        pytest.skip("needs pkg-config")
    env = dict(os.environ, PKG_CONFIG_PATH=str(root / "usr/lib/pkgconfig"))
    cflags = _run(["pkg-config", "--cflags", "contactsim"], env=env).stdout
    includes = [Path(f[2:]).resolve() for f in cflags.split() if f.startswith("-I")]
    assert (root / "usr/include").resolve() in includes, cflags


def test_packaged_server_runs_from_the_unpacked_package(root, tmp_path):
    """Verifies the packaged programs themselves: contactsim-server from the
    unpacked package, on the packaged config (its scene path moved into the
    unpacked root) and a journal folder, loads the packaged default scene;
    the Python client adds a body, steps and reads the state; the packaged
    contactsim-ctl reads the status; SIGINT stops it with status 0 and the
    journal is on disk."""
    config = tmp_path / "server.pbtxt"
    config.write_text((root / "etc/contactsim/server.pbtxt").read_text()
                      .replace('"/usr/share/', '"%s/usr/share/' % root))
    url, prefix = unique_endpoint("DEB")
    journal = tmp_path / "journal"
    log = open(tmp_path / "server.log", "wb")
    cmd = [str(root / "usr/bin/contactsim-server"), "--config", str(config), "--lcm-url", url,
           "--prefix", prefix, "--mode", "free_run", "--paused", "--no-live-line", "--journal", str(journal)]
    with contactsim.Client(url=url, prefix=prefix, timeout=5.0) as sim:
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        try:
            status = sim.wait_for_server(timeout=START_TIMEOUT)
            assert status.version == _control_version(root)
            assert status.num_bodies == 7  # config/scenes/default.pbtxt: ground, 3 balls, 3 crates
            ball = sim.add_sphere(0.1, position=(5, 5, 10), density=1000)
            sim.step(24)
            state = sim.state()
            assert state.step == 24 and len(state.bodies) == 8
            # a free fall of 24 steps of 1/240 s, from rest (semi-implicit Euler)
            assert state.bodies[ball].linear_velocity[2] == pytest.approx(-9.81 * 24 / 240, rel=1e-9)
            ctl = _run([str(root / "usr/bin/contactsim-ctl"), "--lcm-url", url, "--prefix", prefix, "status"])
            assert re.search(r"^bodies: 8$", ctl.stdout, re.M) and re.search(r"^step: 24$", ctl.stdout, re.M), \
                ctl.stdout
        finally:
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
            rc = proc.wait(10)
            log.close()
    assert rc == 0, (tmp_path / "server.log").read_text()[-3000:]
    assert any(journal.iterdir())


def _control_version(root):
    """The version the package was built as, from its CMake package config."""
    text = (root / "usr/lib/cmake/contactsim/contactsimConfigVersion.cmake").read_text()
    return re.search(r'set\(PACKAGE_VERSION "([^"]+)"\)', text).group(1)
