"""Fleets on a local Ray of 2 workers (contactsim.fleet, contactsim.gym;
docs/fleet.md): sweeps match sequential runs hash for hash, a killed
worker's job is retried elsewhere, fork-and-compare gives one row per
method from one snapshot, and the Gymnasium environments step with the
right shapes. One Ray and one fleet serve the whole file (Ray's start-up
is most of its time)."""
import os
import signal
import threading
import time

import numpy as np
import pytest

from conftest import REPO, SERVER_BIN

ray = pytest.importorskip("ray", reason="ray is not importable: the fleet tests need it (make deps installs it)")
pytest.importorskip("pandas", reason="pandas is not importable: fleet results are DataFrames")
pytest.importorskip("gymnasium", reason="gymnasium is not importable: contactsim.gym needs it")

from contactsim.fleet import Fleet, Job, fork_compare, run_sequential  # noqa: E402
from contactsim.gym import ContactsimEnv, FleetVectorEnv, HoverTask  # noqa: E402

SCENES = REPO / "config" / "scenes"
# a job long enough to be killed in the middle of (~2 s on the Release build,
# of which the server uses about 0.2 s of CPU; the test waits for 0.05 s)
LONG_STEPS = 15000


@pytest.fixture(scope="module")
def fleet():
    if not SERVER_BIN.exists():
        pytest.skip("%s is not built (run `make`)" % SERVER_BIN)
    f = Fleet(workers=2, progress=False)
    yield f
    f.close()


def sweep_jobs():
    """8 jobs: two scenes under four method settings."""
    methods = [("impulse", {"iterations": 10}), ("impulse", {"iterations": 40}), ("penalty", {}),
               ("xpbd", {"substeps": 5})]
    return [Job(scene=SCENES / scene, method=m, params=p, steps=120, tag="%s/%s" % (scene, m))
            for scene in ("default.pbtxt", "bounce.pbtxt") for m, p in methods]


# Verifies that the same jobs give the same state hashes on either worker and in a sequential run.
def test_sweep_on_two_workers_matches_a_sequential_run_hash_for_hash(fleet):
    jobs = sweep_jobs()
    df = fleet.map(jobs)
    seq = run_sequential(jobs)
    assert list(df["error"]) == [""] * 8, df["error"].tolist()
    assert list(df["state_hash"]) == list(seq["state_hash"])
    assert set(df["worker"]) == {"w0", "w1"}
    assert (df["final_step"] == 120).all() and (df["ms_per_step"] > 0).all()
    assert len(set(df["state_hash"])) > 1   # the methods do differ


# Verifies that a job the server refuses returns its error in its row, without a retry, beside a good one.
def test_failing_job_returns_its_error_in_its_row(fleet):
    df = fleet.map([Job(scene=SCENES / "bounce.pbtxt", method="no_such_method", steps=10),
                    Job(scene=SCENES / "bounce.pbtxt", steps=10)])
    assert 'unknown contact method "no_such_method"' in df["error"].iloc[0]
    assert df["attempts"].iloc[0] == 1 and df["error"].iloc[1] == ""


def _cpu_seconds(pid):
    fields = open("/proc/%d/stat" % pid).read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


# Verifies that a job whose worker is killed in the middle runs again on the other worker and says so.
def test_job_of_a_killed_worker_is_retried_elsewhere(fleet):
    (_, actor_pid, server_pid), _ = fleet.where()
    job = Job(scene=SCENES / "bounce.pbtxt", method="impulse", steps=LONG_STEPS, tag="long")
    out = {}
    runner = threading.Thread(target=lambda: out.update(df=fleet.map([job])))
    cpu0 = _cpu_seconds(server_pid)
    runner.start()
    deadline = time.monotonic() + 30
    while _cpu_seconds(server_pid) < cpu0 + 0.05 and time.monotonic() < deadline:
        time.sleep(0.02)             # the first worker (w0) is stepping the job now
    os.kill(actor_pid, signal.SIGKILL)
    runner.join(120)
    row = out["df"].iloc[0]
    assert row["error"] == "", row["error"]
    assert row["attempts"] == 2 and "worker died" in row["retried_after"]
    assert row["worker"] == "w1" and row["final_step"] == LONG_STEPS
    with pytest.raises(ProcessLookupError):   # the killed worker's server went with it
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            os.kill(server_pid, 0)
            time.sleep(0.05)


# Verifies that fork_compare runs every method from one snapshot and that its first row continues the world exactly.
def test_fork_compare_gives_one_row_per_method_from_the_same_snapshot(fleet, launch):
    client = launch(scene=SCENES / "default.pbtxt").client
    client.step(60)
    methods = ["impulse", ("penalty", {"kp": 1e5}), "xpbd:substeps=10"]
    df = fork_compare(client, methods, 90, fleet=fleet)
    assert list(df["method"]) == ["impulse", "penalty", "xpbd"]
    assert list(df["error"]) == [""] * 3, df["error"].tolist()
    assert (df["final_step"] == 150).all()
    assert df["departure"].iloc[0] == 0.0 and (df["departure"].iloc[1:] > 0).all()
    for column in ("max_penetration", "energy_drift", "ms_per_step", "mean_contacts"):
        assert np.isfinite(df[column]).all(), column
    # the fork's first method, run on by the original server, gives the same hash
    client.set_contact_method("impulse")
    client.step(90)
    assert "%016x" % (client.state().state_hash & 0xFFFFFFFFFFFFFFFF) == df["state_hash"].iloc[0]


# Verifies that `contactsim-py compare` prints and writes one row per method.
def test_cli_compare_writes_one_row_per_method(fleet, launch, tmp_path, capsys, monkeypatch):
    import pandas as pd
    import contactsim.fleet
    from contactsim.cli import main

    class Borrowed:   # the module's fleet: a second one would wait for CPUs this Ray does not have
        def __init__(self, **kwargs):
            self.workers, self.map = fleet.workers, fleet.map

        def close(self):
            pass
    monkeypatch.setattr(contactsim.fleet, "Fleet", Borrowed)
    server = launch(scene=SCENES / "bounce.pbtxt")
    csv = tmp_path / "cmp.csv"
    assert main(["--lcm-url", server.url, "--prefix", server.prefix, "compare", "impulse", "penalty:kp=100000",
                 "--steps", "30", "--workers", "2", "--csv", str(csv)]) == 0
    table = pd.read_csv(csv)
    assert list(table["method"]) == ["impulse", "penalty"] and table["error"].isna().all()
    assert "penalty kp=100000" in capsys.readouterr().out


# Verifies that the lockstep environment resets to the same start and steps with the declared shapes.
def test_gym_env_resets_and_steps_with_correct_shapes(launch):
    env = ContactsimEnv(launch().client, HoverTask(max_steps=5))
    obs, info = env.reset(seed=1)
    assert obs.shape == env.observation_space.shape == (13,)
    assert env.action_space.shape == (6,)
    rng = np.random.default_rng(1)
    for k in range(5):
        obs, reward, terminated, truncated, info = env.step(rng.uniform(-1, 1, 6))
        assert obs.shape == (13,) and np.isfinite(reward) and not terminated
        assert truncated == (k == 4)
    first, info_first = env.reset()
    again, info_again = env.reset()
    assert np.array_equal(first, again) and info_first["state_hash"] == info_again["state_hash"]
    env.close()


# Verifies that the vectorised environment on the fleet steps both worlds and resets a finished one.
def test_fleet_vector_env_steps_two_worlds(fleet):
    venv = FleetVectorEnv(HoverTask(max_steps=3), num_envs=2, fleet=fleet)
    obs, _ = venv.reset(seed=0)
    assert obs.shape == (2, 13)
    for k in range(3):
        obs, rewards, terminated, truncated, infos = venv.step(np.zeros((2, 6)))
        assert obs.shape == (2, 13) and rewards.shape == (2,)
    assert truncated.all() and set(infos["final_obs"]) == {0, 1}
    venv.close()
