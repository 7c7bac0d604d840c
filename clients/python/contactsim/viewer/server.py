"""The viewer's web server (aiohttp): the page, its scripts, three.js from
the local npm install, the models' mesh files (meshes.py), and the WebSocket
at /ws."""
import asyncio
import json
import logging
import os
from urllib.parse import urlsplit

from aiohttp import WSMsgType, web

from .connection import Connection

HERE = os.path.dirname(os.path.abspath(__file__))
STATIC_DIR = os.path.join(HERE, "static")
THREE_DIR = os.path.join(HERE, "vendor", "node_modules", "three")

log = logging.getLogger("contactsim.viewer")
SOURCE = web.AppKey("source", object)     # the live or replay source
SOCKETS = web.AppKey("sockets", set)      # open WebSockets, closed at shutdown


async def _mesh(request):
    """A mesh file of a model's visual (meshes.py says what is refused)."""
    path = request.app[SOURCE].meshes.resolve(request.match_info["folder"], request.match_info["path"])
    if path is None:
        raise web.HTTPNotFound(text="contactsim-viewer: not a mesh file of a loaded model")
    return web.FileResponse(path)


async def _index(request):
    return web.FileResponse(os.path.join(STATIC_DIR, "index.html"),
                            headers={"Cache-Control": "no-store"})


def _same_origin(request):
    """True unless a browser says the page that opens the socket came from
    elsewhere: WebSockets are exempt from the same-origin policy, so any web
    site open in the user's browser could otherwise command the server."""
    origin = request.headers.get("Origin")
    return origin is None or urlsplit(origin).netloc == request.host


async def _websocket(request):
    if not _same_origin(request):
        raise web.HTTPForbidden(text="contactsim-viewer: WebSocket from another origin refused")
    ws = web.WebSocketResponse(max_msg_size=1 << 20)
    await ws.prepare(request)
    source = request.app[SOURCE]
    conn = Connection(ws, source)
    request.app[SOCKETS].add(ws)
    await conn.send_json(source.hello())
    await conn.send_catalog()
    pusher = asyncio.create_task(conn.push_live()) if source.mode == "live" else None
    try:
        async for msg in ws:
            if msg.type != WSMsgType.TEXT:
                continue
            try:
                await conn.handle(json.loads(msg.data))
            except (ValueError, KeyError, TypeError) as e:
                await conn.send_json({"type": "error", "message": "bad message: %s" % e})
    finally:
        request.app[SOCKETS].discard(ws)
        if pusher is not None:
            pusher.cancel()
    return ws


async def _close_sockets(app):
    # an open page would otherwise hold the shutdown until its timeout
    for ws in list(app[SOCKETS]):
        await ws.close(code=1001, message=b"viewer stopping")


def make_app(source):
    """The aiohttp application serving one source (live or replay)."""
    if not os.path.isfile(os.path.join(THREE_DIR, "build", "three.module.js")):
        log.warning("three.js is not installed in %s: run `make deps`", THREE_DIR)
    app = web.Application()
    app[SOURCE] = source
    app[SOCKETS] = set()
    app.on_shutdown.append(_close_sockets)
    app.router.add_get("/", _index)
    app.router.add_get("/ws", _websocket)
    app.router.add_static("/static/", STATIC_DIR)
    app.router.add_get("/meshes/{folder}/{path:.+}", _mesh)
    if os.path.isdir(THREE_DIR):
        app.router.add_static("/vendor/three/", THREE_DIR)
    return app
