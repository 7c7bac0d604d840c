"""The package puts the generated LCM classes on itself, the way lcm-gen's code expects."""
import os
import subprocess
import sys

import numpy as np

import contactsim
from contactsim import _lcmtypes

from conftest import BUILD, REPO


def test_every_generated_type_is_a_class_attribute():
    for name in _lcmtypes.TYPE_NAMES:
        cls = getattr(contactsim, name)
        assert isinstance(cls, type) and cls.__name__ == name
        assert len(cls._get_packed_fingerprint()) == 8
    assert str(BUILD) in os.path.abspath(_lcmtypes.generated_dir())


def test_generated_folder_holds_exactly_the_known_types():
    lcm_files = sorted(p[:-4] for p in os.listdir(REPO / "lcmtypes") if p.endswith(".lcm"))
    assert lcm_files == sorted(_lcmtypes.TYPE_NAMES)


def test_nested_types_round_trip():
    s = contactsim.state_t()
    s.time, s.step, s.state_hash = 1.5, 360, -42
    for i in range(3):
        b = contactsim.body_state_t()
        b.id = i + 1
        b.position = [i, 2.0 * i, -1.0]
        b.orientation = [1.0, 0.0, 0.0, 0.0]
        s.bodies.append(b)
    s.num_bodies = 3
    st = contactsim.State(contactsim.state_t.decode(s.encode()))
    assert (st.time, st.step, st.state_hash) == (1.5, 360, -42)
    assert list(st.bodies) == [1, 2, 3]
    np.testing.assert_array_equal(st.bodies[3].position, [2.0, 4.0, -1.0])
    assert isinstance(st.bodies[1].orientation, np.ndarray)

    c = contactsim.contacts_t()
    c.method, c.value_kind, c.step = "impulse", contactsim.contacts_t.IMPULSE, 7
    ct = contactsim.contact_t()
    ct.body_a, ct.body_b, ct.normal, ct.depth = 1, 2, [0.0, 0.0, 1.0], 0.001
    c.contacts, c.num_contacts = [ct], 1
    cs = contactsim.Contacts(contactsim.contacts_t.decode(c.encode()))
    assert cs.method == "impulse" and cs.value_kind == "impulse" and len(cs) == 1
    assert cs[0].body_b == 2 and cs[0].depth == 0.001


def test_missing_generated_folder_says_run_make(tmp_path):
    env = dict(os.environ, CONTACTSIM_BUILD_DIR=str(tmp_path / "nowhere"),
               PYTHONPATH=str(REPO / "clients" / "python"))
    r = subprocess.run([sys.executable, "-c", "import contactsim"], env=env,
                       capture_output=True, text=True, cwd=str(tmp_path))
    assert r.returncode != 0
    assert "ImportError" in r.stderr and "make" in r.stderr and "nowhere" in r.stderr
