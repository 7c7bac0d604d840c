#!/usr/bin/env python3
"""Renders the bad-input catalogue (tests/python/bad_input_cases.py) with the
replies a real server gives into a Markdown table.

    .venv/bin/python scripts/bad_input_table.py [--build-dir build] [--write docs/reliability.md]

Starts contactsim-server on the catalogue's scene, sends every case and
prints one row per case: channel, op, case, reply code and message, and
whether the code and message are the expected ones. With --write FILE the
table replaces the lines between the markers
``<!-- bad-input-table:begin -->`` and ``<!-- bad-input-table:end -->``.
"""
import argparse
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(REPO / "tests" / "python"))

import contactsim  # noqa: E402

import bad_input_cases as bad  # noqa: E402
from server_process import ServerProcess  # noqa: E402

BEGIN, END = "<!-- bad-input-table:begin -->", "<!-- bad-input-table:end -->"


def cell(text, limit=110):
    text = text.replace("|", "\\|").replace("\n", " ")
    return text if len(text) <= limit else text[:limit - 1] + "…"


def render(build_dir):
    rows = []
    with tempfile.TemporaryDirectory(prefix="contactsim-badtable-") as tmp:
        bad.write_files(tmp)
        with ServerProcess(build_dir, scene_text=bad.SCENE, tag="BAD", workdir=tmp) as srv:
            srv.client.step(2)
            for case in bad.cases(tmp):
                try:
                    r = case.send(srv.client)
                    code, message = contactsim.errors.CODE_NAMES.get(r.code, str(r.code)), r.message
                    ok = (r.code != 0 if case.code is None else r.code == case.code) and all(
                        w in r.message for w in case.words)
                except contactsim.TimeoutError as e:
                    code, message, ok = "no reply", str(e), False
                message = message.replace(tmp, "<tmp>")
                verdict = "yes" if ok else ("no (known: %s)" % case.gap if case.gap else "no")
                rows.append("| %s | %s | `%s` | %s | %s | %s |" % (
                    case.channel, case.op, case.id, code, cell(message), verdict))
            alive = srv.alive()
        rc = srv.returncode
    head = ["| channel | op | case | reply | message | as expected |", "|---|---|---|---|---|---|"]
    foot = "%d cases; the server %s and exited with status %s." % (
        len(rows), "stayed up" if alive else "DIED", rc)
    return "\n".join(head + rows) + "\n\n" + foot


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build-dir", default=None)
    p.add_argument("--write", default=None, help="a Markdown file with the table markers to update")
    args = p.parse_args(argv)
    table = render(args.build_dir)
    if args.write:
        path = Path(args.write)
        text = path.read_text()
        a, b = text.index(BEGIN) + len(BEGIN), text.index(END)
        path.write_text(text[:a] + "\n" + table + "\n" + text[b:])
    else:
        print(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
