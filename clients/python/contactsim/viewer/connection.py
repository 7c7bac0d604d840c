"""One page's WebSocket: what the bridge sends it and what it asks for
(the messages are listed in docs/viewer.md).

Pose frames are thinned to the page's frame rate with an ack: after one
POSES frame the bridge sends the next only when the page says it drew the
last one, and then the latest STATE only, so a slow page never falls behind.
"""
import asyncio
import json

from .frames import contacts_from_payload, poses_from_catalog, poses_from_records, read_state
from .surface_payload import page_shape, shape_summary

POLL_S = 0.002          # how often the live pusher looks for a new STATE or STATUS


class Connection:
    def __init__(self, ws, source):
        self.ws, self.source = ws, source
        self.ready = True          # the page drew the last POSES frame
        self.catalog_sent = None
        self.snapshot_shown = False  # the poses of a snapshot, before any STATE
        self.tasks = set()

    async def send_json(self, obj):
        if not self.ws.closed:
            await self.ws.send_str(json.dumps(obj))

    async def send_bytes(self, data):
        if not self.ws.closed:
            await self.ws.send_bytes(data)

    async def send_catalog(self):
        if self.catalog_sent != self.source.catalog_version:
            self.catalog_sent = self.source.catalog_version
            # tens of ms for a large heightfield: off the event loop
            text = await asyncio.to_thread(catalog_message, self.source.catalog)
            if not self.ws.closed:
                await self.ws.send_str(text)

    async def push_live(self):
        """Sends STATUS when it changes, the catalog when it changes, each new
        ray cast, and the latest STATE (with the latest CONTACTS and range
        sensor fans) whenever the page is ready."""
        client = self.source.client
        last_count = last_status = last_contacts = None
        last_cast, last_sensors = 0, None
        while not self.ws.closed:
            await asyncio.sleep(POLL_S)
            status = client.status()
            if status is not None and status is not last_status:
                last_status = status
                await self.send_json(status_message(status))
            # a ray cast comes whenever a client casts, paused or not
            last_cast = await self._send_cast(last_cast)
            if not self.ready:
                continue
            reading = client.sensors()   # published with STATE: thinned like it, by the page's ack
            if reading is not None and reading is not last_sensors:
                last_sensors = reading
                await self.send_bytes(self.source.sensors_frame(reading))
            payload, count = client.state_payload()
            if payload is None:
                await self._first_from_snapshot()
                continue
            parsed = read_state(payload) if count != last_count else None
            last_count = count
            if parsed is None:
                continue
            head, bodies = parsed
            self.source.note_state(int(head["step"]), bodies["id"])
            await asyncio.to_thread(self.source.refresh_catalog)
            await self.send_catalog()
            contacts, contacts_count = client.contacts_payload()
            if contacts is not None and contacts_count != last_contacts:
                last_contacts = contacts_count
                frame = contacts_from_payload(contacts)
                if frame is not None:
                    await self.send_bytes(frame)
            self.ready = False
            await self.send_bytes(poses_from_records(head, bodies))

    async def _send_cast(self, last_cast):
        """Sends the newest ray cast when it is new; returns the count sent."""
        count, frame = self.source.cast_frame()
        if frame is not None and count != last_cast:
            await self.send_bytes(frame)
            return count
        return last_cast

    async def _first_from_snapshot(self):
        """A paused server publishes no STATE until something changes: show
        the poses of the catalog's snapshot meanwhile, once."""
        if self.snapshot_shown:
            return
        await asyncio.to_thread(self.source.refresh_catalog)
        if self.source.catalog_version > 0:
            self.snapshot_shown = True
            await self.send_catalog()
            self.ready = False
            await self.send_bytes(poses_from_catalog(self.source.catalog))

    async def handle(self, msg):
        """One JSON message from the page."""
        cmd = msg.get("cmd")
        if cmd == "ack":
            self.ready = True
        elif cmd == "seek":
            i = max(0, min(int(msg["index"]), len(self.source.log.step) - 1))
            status = self.source.status(i)
            if status is not None:
                await self.send_json(status)
            await self.send_bytes(self.source.contacts(i))
            await self.send_bytes(self.source.poses(i))
        elif cmd == "body":
            info = await asyncio.to_thread(self.source.body_info, int(msg["id"]))
            if "shape" in info:
                info["shape"] = shape_summary(info["shape"])
            await self.send_json({"type": "body", **info})
        else:
            task = asyncio.create_task(self._command(msg))
            self.tasks.add(task)
            task.add_done_callback(self.tasks.discard)

    async def _command(self, msg):
        """Runs a command off the event loop (the client waits for its reply)."""
        if not hasattr(self.source, "command"):
            ok, text = False, "a replay takes no commands"
        else:
            try:
                ok, text = True, await asyncio.to_thread(self.source.command, msg)
            except Exception as e:  # noqa: BLE001 - every failure goes back to the page as text
                ok, text = False, str(e) or type(e).__name__
        await self.send_json({"type": "reply", "id": msg.get("id"), "cmd": msg.get("cmd"), "ok": ok,
                              "message": text})


def catalog_message(catalog):
    """The catalog message's JSON text, its surfaces packed (surface_payload.py)."""
    bodies = [{**b, "shape": page_shape(b["shape"])} for b in catalog["bodies"]]
    return json.dumps({"type": "catalog", **catalog, "bodies": bodies})


def status_message(status):
    """STATUS as JSON for the page's panel (the fields it shows)."""
    keys = ("paused", "method", "method_params", "method_contract", "time", "step", "dt", "step_rate", "real_time_factor",
            "num_bodies", "num_contacts", "max_penetration", "last_error", "version")
    out = {k: getattr(status, k) for k in keys}
    out.update(type="status", mode=status.mode)
    return out
