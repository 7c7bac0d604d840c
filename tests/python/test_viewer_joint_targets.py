"""contactsim-viewer's joint sliders in a real browser (headless chromium,
Selenium) against a real server (docs/viewer.md, "Joint panel"): a slider
sets a joint's actuator target through the bridge and the joint goes
there. Skipped without chromium, chromedriver or selenium."""
from test_viewer import VIEWER, browser, open_page  # noqa: F401 - the browser fixture

from contactsim.viewer.headless import wait_for
from contactsim.viewer.process import ViewerProcess

# a fixed base and two arms on hinges about z (no gravity acts along them), the elbow unactuated
ARM = """<robot name="arm">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="upper"><inertial><origin xyz="0.25 0 0"/><mass value="1"/>
    <inertia ixx="0.001" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.4 0.05 0.05"/></geometry></collision></link>
  <link name="fore"><inertial><origin xyz="0.2 0 0"/><mass value="0.5"/>
    <inertia ixx="0.001" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.2 0 0"/><geometry><box size="0.3 0.05 0.05"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="100" velocity="10"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0.5 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="100" velocity="10"/></joint>
</robot>"""
TARGET = 0.8        # rad
SETTLE_STEPS = 720  # 3 s at 240 Hz: the drive's time constant kd / kp is 0.2 s
TOLERANCE = 1e-3    # rad: the drive has no gravity or load to hold against, so it reaches the target


def _slide(driver, joint, value):
    """Moves a joint's slider as a drag does: a new value and its input
    event; returns the value the slider took (a multiple of its step)."""
    return driver.execute_script(
        "const s = document.querySelector(`#joints input[data-joint='${arguments[0]}']`);"
        "s.value = arguments[1]; s.dispatchEvent(new Event('input')); return Number(s.value);", joint, value)


# Verifies that dragging the shoulder's slider sends its target through the
# bridge (ACTUATOR_CMD SET of the target alone: the drive keeps its gains,
# so the joint goes there), that JOINT_STATE and the page's own joint angle
# then read the target, and that the elbow, whose actuator has no position
# gain, shows a disabled slider.
def test_a_slider_drives_its_joint_to_the_target(server, browser):  # noqa: F811
    c = server.client
    c.set_gravity((0, 0, 0))
    arm = c.load_model(ARM, name="arm", fixed_base=True)
    shoulder, elbow = arm.joint_id("shoulder"), arm.joint_id("elbow")
    c.set_joint_actuator(shoulder, kp=50.0, kd=10.0, target_position=0.0)
    c.set_joint_actuator(elbow, kd=1.0)
    c.step(1)
    with ViewerProcess(["--lcm-url", server.url, "--prefix", server.prefix]) as viewer:
        open_page(browser, viewer.url, c.state().step)
        enabled = browser.execute_script(
            "return Object.fromEntries([...document.querySelectorAll('#joints input')].map(s => [s.dataset.joint, !s.disabled]))")
        assert enabled == {str(shoulder): True, str(elbow): False}
        target = _slide(browser, shoulder, TARGET)
        assert abs(target - TARGET) < 0.01
        targets = wait_for(browser, "%s.jointTargets()['arm/shoulder'] !== undefined && %s.jointTargets()"
                           % (VIEWER, VIEWER))
        assert targets["arm/shoulder"] == target
        c.step(SETTLE_STEPS)
        positions, _, _ = c.request_joint_state().of_joints([shoulder, elbow])
        assert abs(positions[0] - target) < TOLERANCE, positions
        step = c.state().step
        wait_for(browser, "%s.step() === %d" % (VIEWER, step))
        drawn = browser.execute_script("return %s.jointValues()" % VIEWER)
        assert abs(drawn["arm/shoulder"] - positions[0]) < 1e-6
