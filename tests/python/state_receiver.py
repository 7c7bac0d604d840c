"""Counts STATE messages in a process of its own (used by test_scale.py).

    python state_receiver.py URL CHANNEL MIN_BODIES

Prints "ready" once subscribed, receives until stdin closes, then prints one
JSON object: for every STATE, [step, num_bodies, complete], where complete
means at least MIN_BODIES bodies, num_bodies == len(bodies) and ids strictly
ascending. Payloads that do not decode count as incomplete.
"""
import json
import sys
import threading

import lcm

import contactsim


def main():
    url, channel, min_bodies = sys.argv[1], sys.argv[2], int(sys.argv[3])
    records, undecodable = [], 0
    lc = lcm.LCM(url)

    def on_state(ch, data):
        nonlocal undecodable
        try:
            m = contactsim.state_t.decode(data)
        except Exception:  # noqa: BLE001 - counted
            undecodable += 1
            return
        ids = [b.id for b in m.bodies]
        complete = (m.num_bodies >= min_bodies and len(ids) == m.num_bodies
                    and all(a < b for a, b in zip(ids, ids[1:])))
        records.append([m.step, m.num_bodies, complete])

    lc.subscribe(channel, on_state)
    done = threading.Event()
    threading.Thread(target=lambda: (sys.stdin.read(), done.set()), daemon=True).start()
    print("ready", flush=True)
    while not done.is_set():
        lc.handle_timeout(50)
    print(json.dumps({"records": records, "undecodable": undecodable}), flush=True)


if __name__ == "__main__":
    main()
