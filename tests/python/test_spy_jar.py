"""lcm-spy decodes every channel with the build's jar of message classes.

Records a real server on every channel (test_logged_channels.py's run) and
decodes the log with tests/java/DecodeLog.java, which looks each event's
class up by fingerprint in lcm-spy's own type database, as lcm-spy does
(docs/packaging.md, "lcm-spy").
"""
import shutil
import subprocess

import pytest

from conftest import BUILD, REPO
from test_logged_channels import CHANNELS, record_every_channel

LCM_JAR = "/usr/share/java/lcm.jar"  # Debian's liblcm-java, the jar's compile class path too
JAR = BUILD / "lcmtypes" / "contactsim_lcmtypes.jar"
TYPES = {"BODY_CMD": "body_cmd_t", "SCENE_CMD": "scene_cmd_t", "JOINT_CMD": "joint_cmd_t",
         "INPUT": "input_t", "REPLY": "reply_t", "STATE": "state_t", "CONTACTS": "contacts_t",
         "STATUS": "status_t", "MODEL_CMD": "model_cmd_t", "MODEL_INFO": "model_info_t",
         "ACTUATOR_CMD": "actuator_cmd_t", "JOINT_STATE": "joint_state_t"}
JAVA_TIMEOUT = 60  # javac and a JVM start on two busy cores
RECORD_TRIES = 3  # a log that lost a channel's messages on UDP is recorded again


def test_every_recorded_channel_decodes_with_the_jar(server, tmp_path):
    if not shutil.which("javac") or not shutil.which("java"):
        pytest.skip("no JDK (make deps installs default-jdk-headless)")
    assert JAR.exists(), "%s is not built (cmake/lcmtypes_java.cmake)" % JAR
    classpath = "%s:%s" % (LCM_JAR, JAR)
    subprocess.run(["javac", "-nowarn", "-cp", classpath, "-d", str(tmp_path),
                    str(REPO / "tests" / "java" / "DecodeLog.java")], check=True, timeout=JAVA_TIMEOUT)
    regex = "%s_(%s)" % (server.prefix, "|".join(CHANNELS))
    wanted = [server.prefix + "_" + suffix for suffix in CHANNELS]
    for attempt in range(RECORD_TRIES):
        log = tmp_path / ("run%d.lcmlog" % attempt)
        record_every_channel(server, log)
        r = subprocess.run(["java", "-cp", "%s:%s" % (classpath, tmp_path), "DecodeLog", str(log), regex],
                           capture_output=True, text=True, timeout=JAVA_TIMEOUT)
        assert r.returncode == 0, r.stdout + r.stderr
        decoded = {line.split()[0]: line.split()[1:] for line in r.stdout.splitlines()}
        if all(ch in decoded for ch in wanted):
            break
    missing = [ch for ch in wanted if ch not in decoded]
    assert not missing, "every recording lost %s on UDP" % missing
    for suffix in CHANNELS:
        cls, count = decoded[server.prefix + "_" + suffix]
        assert cls == "contactsim." + TYPES[suffix] and int(count) > 0
