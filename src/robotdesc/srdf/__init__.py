"""The self-collision matrix MoveIt's Setup Assistant computes, without ROS.

`compute_matrix` samples random configurations within the joint limits (mimic joints follow
their drivers), checks every link pair's collision geometry with coal, and classifies pairs
as Adjacent, Default, Always or Never; `render_srdf` and `render_report` write the results.
Needs Pinocchio (`robotdesc[kinematics]`). See docs/kinematics.md.
"""

from robotdesc.srdf.matrix import CollisionMatrix, PairResult, Reason, compute_matrix
from robotdesc.srdf.write import render_report, render_srdf

__all__ = ["CollisionMatrix", "PairResult", "Reason", "compute_matrix", "render_report",
           "render_srdf"]
