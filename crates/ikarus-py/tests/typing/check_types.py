"""Type-checked, not run: mypy (``crates/ikarus-py/test``) reads this with ``--strict
--warn-unused-ignores``, so each line below must type-check, and each line marked ``type:
ignore[code]`` must be the error of that code: a wrong method name, an unknown option, a
positional option. If the stub's types loosened, the ignores would be unused and mypy fail."""

import numpy as np

import ikarus

arm = ikarus.Chain()
out: ikarus.Outcome = arm.solve((2.0, 3.0), method="dls", lambda_=0.2, limits=True, limit_mode="lock")
tips: tuple[ikarus.Effector, ...] = out.effectors
rig = ikarus.Rig.shipped("puppet")
solved: ikarus.Outcome = rig.solve({"right_hand": (0.6, 1.0), "left_hand": {"x": 0.8, "y": 0.5, "weight": 2.0}}, pins=["left_foot"], restarts=0)
motion: ikarus.Motion = arm.animate((2.0, 3.0), frames=5, ease="smoothstep", interpolation="linear")
frames: ikarus.MotionFrames = rig.animate({"right_hand": (0.6, 1.0)}, pins=["left_foot"]).frames
track: ikarus.Track = rig.track("right_hand", circle=(0.3, 0.8, 0.2), samples=5, solver_max_step_deg=10.0)
samples: ikarus.TrackSamples = arm.track(figure8=(2.0, 1.0, 2.0), mode="plan").samples
summary: ikarus.TrackSummary = track.summary
batch = arm.solve_batch(np.zeros((3, 2)), threads=2, method="lm")
status: np.ndarray = batch["status"]
options: ikarus.SolveOptions = {"method": "sdls", "restarts": 4}
arm.solve((1.0, 1.0), **options)
boy = ikarus.Rig.from_file("spineboy.json")
walked: ikarus.CharacterMotion = boy.character_motion(keys={"fps": 30, "tracks": {}}, animation="walk")
rows: np.ndarray = walked.x
posed: ikarus.Pose = walked.pose(0)
atlas: ikarus.Atlas = ikarus.Atlas.read("spineboy.atlas")
png: bytes = boy.picture(atlas, "walk", 0.4, {"front-leg-target": (60.0, 20.0)}, art_only=True, width=400)
pixels: np.ndarray = boy.image(atlas, skin="default", physics=False)
spine: str = boy.export_spine({"front-leg-target": (120.0, 40.0)}, duration=0.5, ease="sine", animation_name="ikarus")

arm.solve((2.0, 3.0), method="lmm")  # type: ignore[arg-type]
arm.solve((2.0, 3.0), lamda=0.1)  # type: ignore[call-arg]
rig.animate({"right_hand": (0.6, 1.0)}, limit_mode="lok")  # type: ignore[arg-type]
arm.track(figure8=(2.0, 1.0, 2.0), mode="glide")  # type: ignore[arg-type]
arm.solve_batch(np.zeros((3, 2)), 2)  # type: ignore[misc]
arm.workspace(True)  # type: ignore[misc]
arm.animate((2.0, 3.0), ease="bounce")  # type: ignore[arg-type]
arm.animate((2.0, 3.0), framez=3)  # type: ignore[call-arg]
rig.track("right_hand", circle=(0.3, 0.8, 0.2), solver_max_step="10")  # type: ignore[call-arg]
boy.character_motion({"front-leg-target": (120.0, 40.0)}, ease="bounce")  # type: ignore[arg-type]
boy.export_spine({"front-leg-target": (120.0, 40.0)}, 0.5)  # type: ignore[misc, arg-type]
boy.picture(atlas, art_onyl=True)  # type: ignore[call-arg]
boy.image("spineboy.atlas")  # type: ignore[arg-type]
