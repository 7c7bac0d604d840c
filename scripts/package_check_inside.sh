#!/usr/bin/env bash
# The steps of scripts/package_check.sh, inside the throwaway root (as root,
# no systemd: postinst makes the state folder itself). Prints each step and
# fails at the first check that does not hold.
set -euo pipefail
URL="udpm://239.255.76.67:7699?ttl=0&recv_buf_size=8388608"
PREFIX="PKGCHECK$$"
CTL=(contactsim-ctl --lcm-url "$URL" --prefix "$PREFIX")
fail() { echo "package-check: FAIL: $*" >&2; exit 1; }
step() { echo "package-check: $*"; }

start_server() {  # the installed server, as the service user, as the unit starts it
  # setpriv execs the server (runuser would stay its parent and keep SIGINT from it)
  setpriv --reuid=contactsim --regid=contactsim --init-groups /usr/bin/contactsim-server --config /etc/contactsim/server.pbtxt \
    --journal /var/lib/contactsim/journal --no-live-line --lcm-url "$URL" --prefix "$PREFIX" \
    --mode free_run --paused >/tmp/server.log 2>&1 &
  SERVER=$!
  "${CTL[@]}" --timeout 15 status >/tmp/status || { cat /tmp/server.log; fail "no STATUS from the server"; }
}
stop_server() {  # SIGINT, the unit's KillSignal: a clean stop, exit 0
  kill -INT "$SERVER"
  wait "$SERVER" || { cat /tmp/server.log; fail "server exited with $?"; }
}
field() { sed -n "s/^$1: //p" /tmp/status; }

step "install (apt, with the runtime dependencies)"
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends /tmp/contactsim.deb >/tmp/apt.log \
  || { tail -20 /tmp/apt.log; fail "apt-get install"; }
dpkg -s contactsim | grep -q '^Status: install ok installed' || fail "not installed"
getent passwd contactsim >/dev/null || fail "no user contactsim"
[ "$(stat -c %U /var/lib/contactsim)" = contactsim ] || fail "/var/lib/contactsim not owned by contactsim"
[ -f /lib/systemd/system/contactsim.service ] || fail "no systemd unit"
[ -f /usr/share/java/contactsim_lcmtypes.jar ] || fail "no lcm-spy jar"

step "run /usr/bin/contactsim-server on /etc/contactsim/server.pbtxt"
start_server
[ "$(field bodies)" = 7 ] || fail "default scene: $(field bodies) bodies, not 7"
"${CTL[@]}" add sphere --radius 0.1 --position 5 5 10 --density 1000 >/dev/null || fail "add sphere"
"${CTL[@]}" step 24 >/dev/null || fail "step"
"${CTL[@]}" --timeout 5 status >/tmp/status
[ "$(field bodies)" = 8 ] && [ "$(field step)" = 24 ] || fail "after add and step: $(cat /tmp/status)"
stop_server
ls /var/lib/contactsim/journal | grep -q . || fail "no journal written"

step "upgrade by reinstalling: the edited conffile stays, the world is recovered"
echo "# edited by package-check" >>/etc/contactsim/server.pbtxt
dpkg -i /tmp/contactsim.deb >/tmp/dpkg.log 2>&1 || { cat /tmp/dpkg.log; fail "dpkg -i"; }
grep -q "edited by package-check" /etc/contactsim/server.pbtxt || fail "conffile edit lost on upgrade"
start_server
[ "$(field bodies)" = 8 ] && [ "$(field step)" = 24 ] || fail "not recovered from the journal: $(cat /tmp/status)"
stop_server

step "remove: the journal and the config stay"
DEBIAN_FRONTEND=noninteractive apt-get remove -y -qq contactsim >/dev/null
[ ! -e /usr/bin/contactsim-server ] || fail "server still installed"
ls /var/lib/contactsim/journal | grep -q . || fail "journal gone on remove"
[ -f /etc/contactsim/server.pbtxt ] || fail "conffile gone on remove"

step "purge: the journal and the config go, the system user stays"
dpkg --purge contactsim >/dev/null
[ ! -e /var/lib/contactsim ] || fail "/var/lib/contactsim left after purge"
[ ! -e /etc/contactsim/server.pbtxt ] || fail "conffile left after purge"
getent passwd contactsim >/dev/null || fail "system user removed"
step "ok"
