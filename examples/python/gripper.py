"""A force-controlled gripper driven from Python (issue 40).

A soft FE ball (meshes/ball_5cm.msh, co-rotational, r = 5 cm) rests on a plane between two kinematic
fingers (boxes) with friction mu on the finger pairs (the scene: examples/python/gripper.opts). The
script steers the fingers from the contact forces it reads each step:

1. settle: the ball comes to rest on the plane under gravity, the fingers still;
2. squeeze: each finger closes on the ball with a proportional force controller: from the normal
   contact force F it measured in the last step (scene.contacts(): the sum of the normal forces of
   the contacts whose pair involves that finger), it steps by gain * (target - F), limited to
   max_speed * h, through Body.set_pose (the pose at the end of the next step), until both forces
   are within tolerance of the target for a few steps running;
3. hold: the same control, the fingers' height fixed, for the rest of grip_steps (squeeze and hold);
4. lift: both fingers rise by lift_height (a smooth start and stop, lift_speed on average), still
   force-controlled;
5. carry: the fingers held up, still force-controlled: the ball hangs by friction alone.

It prints the force reached on each finger against the target, and the ball's lift against the
fingers' (a ball that slipped would lag behind the fingers or drop). With mu F per finger the
friction holds up to 2 mu F, which the default target puts well above the ball's weight.

Run it from the repository root (build it first: scripts/build.sh):
    /usr/bin/python3 examples/python/gripper.py [--output out/gripper.h5] [--target 4] [--json f.json]
    mpirun -n 2 /usr/bin/python3 examples/python/gripper.py
run_gripper() does the same from a program or a test (tests/test_python_examples.py)."""
import argparse
import json
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))
import fecontact  # noqa: E402  (before petsc4py: python/fecontact/_lib.py)

SCENE = os.path.join(ROOT, "examples", "python", "gripper.opts")
FINGERS = ("left", "right")
SIDE = {"left": -1.0, "right": 1.0}  # the side of the ball each finger is on, along x


def finger_forces(scene):
    """The normal contact force (N) on each finger: the sum of the normal components of the forces of
    the last step's contacts whose pair involves the finger"""
    c = scene.contacts()
    return {f: float(sum(c["force_local"][k, 0] for k, p in enumerate(c["pairs"]) if f in p)) for f in FINGERS}


def ground_force(scene):
    c = scene.contacts()
    return float(sum(c["force_local"][k, 0] for k, p in enumerate(c["pairs"]) if "ground" in p))


def run_gripper(output_file="out/gripper.h5", target=4.0, mu=1.0, gain=2e-4, max_speed=0.02, tolerance=0.01,
                time_step=0.005, settle_steps=20, grip_steps=120, lift_height=0.03, lift_speed=0.1, carry_steps=40,
                options=None, comm=None, log=None):
    """Run the gripper scene and return its figures (the same on every rank):
    target, weight (the ball's, N), force_reached (finger -> mean normal force over the hold's last
    half, N), hold_error (the largest relative error of a finger's force over the hold), lift_error
    (the same over the lift and the carry), squeeze_steps (to reach the target; None if it was not
    reached within grip_steps, the hold then the last 20 steps of them), hold_steps, finger_lift and
    ball_lift (m, from the start of the lift to the end of the carry), carry_slip (m, how much the ball
    slid down the fingers over the carry's second half), ball_min_z (its lowest vertex at the end, m),
    ground_force (N, at the end), forces (per step: the time, both fingers' forces, the fingers' and
    the ball's heights). options: more options for the scene (a dict), e.g. {"ball_young": 1e5}."""
    if os.path.dirname(output_file):
        os.makedirs(os.path.dirname(output_file), exist_ok=True)
    n_lift = int(round(lift_height / (lift_speed * time_step)))
    opts = {"ball_dm_plex_filename": os.path.join(ROOT, "meshes", "ball_5cm.msh"), "contact_mu": "0.3,%r,%r" % (mu, mu),
            "time_step": time_step, "time_steps": settle_steps + grip_steps + n_lift + carry_steps,
            "output_file": output_file, "quiet": None}
    opts.update(options or {})
    say = log or (lambda *a: None)
    with fecontact.Scene(options=opts, options_file=SCENE, comm=comm) as scene:
        scene.setup()  # the bodies are placed at set-up: their poses before it read as zeros
        h = scene.time_step
        ball = scene.body("ball")
        fingers = {f: scene.body(f) for f in FINGERS}
        pos = {f: fingers[f].centroid.copy() for f in FINGERS}
        history = []

        def control(lift=0.0):
            """One step: each finger's new x from its force, its z raised by lift"""
            force = finger_forces(scene)
            for f in FINGERS:
                dx = np.clip(gain * (target - force[f]), -max_speed * h, max_speed * h)
                pos[f][0] -= SIDE[f] * dx  # towards the ball where the force is short of the target
                pos[f][2] += lift
                fingers[f].set_pose(pos[f])
            scene.step()
            force = finger_forces(scene)
            history.append((scene.time, force["left"], force["right"], pos["left"][2], ball.centroid[2]))
            return force

        scene.step(settle_steps)
        # the ball's weight m g: its gravity energy m g z over its centroid's height z
        weight = ball.energy["gravity"] / ball.centroid[2]
        say("settled: ball at z = %.4f m, weight %.3f N, ground force %.3f N" %
            (ball.centroid[2], weight, ground_force(scene)))
        within, squeeze = 0, 0
        while within < 5 and squeeze < grip_steps:
            force = control()
            squeeze += 1
            within = within + 1 if all(abs(force[f] - target) <= tolerance * target for f in FINGERS) else 0
        say("squeeze: %d steps, forces %s N" % (squeeze, ", ".join("%.3f" % v for v in force.values())))
        hold = [control() for _ in range(grip_steps - squeeze)]
        if within < 5:  # not reached: the figures of the grip's last steps
            squeeze, hold = None, [dict(zip(FINGERS, r[1:3])) for r in history[-20:]]
        z_ball0, z_finger0 = ball.centroid[2], pos["left"][2]
        # a smooth rise, z = lift_height (1 - cos(pi s)) / 2 over s in [0, 1], at lift_speed on average: a sudden
        # start or stop shakes the hanging ball and its contact forces
        rise = np.diff(lift_height * (1 - np.cos(np.pi * np.arange(n_lift + 1) / n_lift)) / 2)
        lifting = [control(dz) for dz in rise]
        lifting += [control() for _ in range(carry_steps // 2)]
        gap_carry0 = pos["left"][2] - ball.centroid[2]  # once the lift's sway has died down: a slip goes on
        lifting += [control() for _ in range(carry_steps - carry_steps // 2)]
        z_ball1 = ball.centroid[2]
        figures = dict(
            target=target, mu=mu, weight=weight, time_step=h, squeeze_steps=squeeze, hold_steps=len(hold),
            force_reached={f: float(np.mean([s[f] for s in hold[len(hold) // 2:]])) for f in FINGERS},
            hold_error=max(abs(s[f] - target) / target for s in hold for f in FINGERS),
            lift_error=max(abs(s[f] - target) / target for s in lifting for f in FINGERS),
            finger_lift=float(pos["left"][2] - z_finger0), ball_lift=float(z_ball1 - z_ball0),
            carry_slip=float((pos["left"][2] - z_ball1) - gap_carry0),
            ball_min_z=float(ball.positions[:, 2].min()), ground_force=ground_force(scene),
            steps=scene.step_index, forces=[list(map(float, r)) for r in history])
        scene.finish()
    return figures


def report(fig, out=print):
    out("target %.3f N per finger (mu %.2f: friction holds up to 2 mu F = %.2f N; ball weight %.3f N)" %
        (fig["target"], fig["mu"], 2 * fig["mu"] * fig["target"], fig["weight"]))
    for f in FINGERS:
        out("  %-5s finger: %.4f N reached (%+.2f %% of the target)" %
            (f, fig["force_reached"][f], 100 * (fig["force_reached"][f] / fig["target"] - 1)))
    out("  %s; largest force error over the hold (%d steps) %.2f %%, over the lift and carry %.2f %%" %
        ("reached in %d squeeze steps of %g s" % (fig["squeeze_steps"], fig["time_step"]) if fig["squeeze_steps"]
         else "NOT reached", fig["hold_steps"], 100 * fig["hold_error"], 100 * fig["lift_error"]))
    out("lift: fingers %.2f mm, ball %.2f mm (lags by %.2f mm), slid %.3f mm down the fingers over the carry's "
        "second half; lowest point %.2f mm above the plane, ground force %.3g N" %
        (1e3 * fig["finger_lift"], 1e3 * fig["ball_lift"], 1e3 * (fig["finger_lift"] - fig["ball_lift"]),
         1e3 * fig["carry_slip"], 1e3 * fig["ball_min_z"], fig["ground_force"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--output", default="out/gripper.h5", help="the run's HDF5 file (default out/gripper.h5)")
    ap.add_argument("--target", type=float, default=4.0, help="normal force per finger (N, default 4)")
    ap.add_argument("--mu", type=float, default=1.0, help="friction coefficient of the fingers (default 1)")
    ap.add_argument("--json", help="write the figures to this JSON file (rank 0)")
    a = ap.parse_args()
    from petsc4py import PETSc
    rank = PETSc.COMM_WORLD.rank
    say = print if rank == 0 else (lambda *x: None)
    fig = run_gripper(a.output, target=a.target, mu=a.mu, log=say)
    report(fig, say)
    if a.json and rank == 0:
        with open(a.json, "w") as f:
            json.dump(fig, f, indent=1)


if __name__ == "__main__":
    main()
