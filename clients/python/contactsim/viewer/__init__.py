"""contactsim-viewer: a web page that watches, steers and replays a
contactsim world (docs/viewer.md).

The bridge is a contactsim.Client like any other: it reads STATE, CONTACTS
and STATUS over LCM and serves a three.js page and a WebSocket with aiohttp.
``contactsim-viewer --log FILE`` replays an lcm-logger log instead.
"""
