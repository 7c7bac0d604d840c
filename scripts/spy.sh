#!/usr/bin/env bash
# Starts lcm-spy with the jar of contactsim's message classes on its class
# path, so that it decodes every channel (make spy; docs/packaging.md).
#   scripts/spy.sh BUILD_DIR [lcm-spy options, e.g. --lcm-url=URL]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
shift || true
JAR=$(realpath -m "$BUILD/lcmtypes/contactsim_lcmtypes.jar")
if [ ! -f "$JAR" ]; then
  echo "spy: $JAR is not built (make; it needs the JDK and liblcm-java that make deps installs)" >&2
  exit 1
fi
# The lcm wheel's lcm-spy (in .venv) brings the charting jars Debian does not
# package and appends $CLASSPATH; Debian's lcm-spy script passes -Xincgc,
# which Java 17 refuses, so without .venv java runs Debian's lcm.jar itself.
if [ -x .venv/bin/lcm-spy ]; then
  CLASSPATH="$JAR" exec .venv/bin/lcm-spy "$@"
fi
exec java -Djava.net.preferIPv4Stack=true -cp "/usr/share/java/lcm.jar:$JAR" lcm.spy.Spy "$@"
