"""contactsim-viewer: watch, steer and replay a contactsim world in a browser.

    contactsim-viewer [--host 127.0.0.1] [--port 8765] [--lcm-url URL] [--prefix P] [--auth-key-file FILE]
    contactsim-viewer --log FILE [--snapshot FILE]      # replay an lcm-logger log, no server needed

Prints the page's URL, then serves until Ctrl-C (docs/viewer.md).
"""
import argparse
import asyncio
import os
import signal
import sys

REPO_SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), *[os.pardir] * 4, "config", "scenes")


def _parser():
    p = argparse.ArgumentParser(prog="contactsim-viewer", description=__doc__.split("\n")[0])
    p.add_argument("--host", default="127.0.0.1", help="address to bind (default: this host only)")
    p.add_argument("--port", type=int, default=8765, help="HTTP port (0: any free one)")
    p.add_argument("--lcm-url", default=None, help="LCM URL (default: $LCM_DEFAULT_URL or project default)")
    p.add_argument("--prefix", default="CONTACTSIM", help="channel prefix")
    p.add_argument("--timeout", type=float, default=5.0, help="reply timeout of commands, s")
    p.add_argument("--auth-key-file", default=None, metavar="FILE",
                   help="sign commands and check the server's signatures (default: $CONTACTSIM_AUTH_KEY_FILE)")
    p.add_argument("--scenes", default=os.path.normpath(REPO_SCENES), metavar="DIR",
                   help="scene files offered by the page's load list (paths on the server's host)")
    p.add_argument("--log", default=None, metavar="FILE", help="replay this lcm-logger log instead of a server")
    p.add_argument("--snapshot", default=None, metavar="FILE", help="replay: shapes from this snapshot file")
    return p


def _source(a):
    if a.log:
        from .replay import ReplaySource
        return ReplaySource(a.log, snapshot_path=a.snapshot, prefix=None if a.prefix == "CONTACTSIM" else a.prefix)
    from ..client import Client
    from .live import LiveSource
    client = Client(url=a.lcm_url, prefix=a.prefix, timeout=a.timeout, client_id=None,
                    auth_key_file=a.auth_key_file)
    return LiveSource(client, scenes_dir=a.scenes)


async def _serve(a, source):
    from aiohttp import web

    from .server import make_app
    runner = web.AppRunner(make_app(source), handle_signals=False)
    await runner.setup()
    site = web.TCPSite(runner, a.host, a.port)
    await site.start()
    host, port = runner.addresses[0][:2]
    shown = "127.0.0.1" if host in ("0.0.0.0", "::") else host
    print("contactsim-viewer: http://%s:%d/ (%s)" % (shown, port, "replay of %s" % a.log if a.log
                                                    else "live, prefix %s" % a.prefix), flush=True)
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    await stop.wait()
    await runner.cleanup()


def main(argv=None):
    a = _parser().parse_args(argv)
    try:
        source = _source(a)
    except (OSError, ValueError) as e:
        print("contactsim-viewer: %s" % e, file=sys.stderr)
        return 2
    try:
        asyncio.run(_serve(a, source))
    finally:
        source.close()
        if hasattr(source, "client"):
            source.client.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
