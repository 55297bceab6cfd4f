"""Which collision geometry the simulation uses: as written, the visuals, or generated.

- "as-is": the `<collision>` elements as written.
- "visual": the `<visual>` geometry used as collision (what a model without collision
  meshes costs; the Engineer papers measured a real-time factor of about 0.2 this way).
- "generated": robotdesc's `generate_collision` (from the visual meshes); links it does not
  cover keep their collision geometry as written.
"""

from __future__ import annotations

import dataclasses
import logging
from typing import Any, Mapping, Sequence

from robotdesc.collision import generate_collision
from robotdesc.collision.methods import DEFAULT_METHOD
from robotdesc.model.elements import Collision, Robot

log = logging.getLogger(__name__)

COLLISION_MODES = ("as-is", "visual", "generated")


def visual_as_collision(robot: Robot) -> Robot:
    """A copy of `robot` whose collision geometry is its visual geometry."""
    return dataclasses.replace(robot, links=tuple(
        dataclasses.replace(link, collisions=tuple(
            Collision(visual.name, visual.origin, visual.geometry, visual.where)
            for visual in link.visuals)) for link in robot.links))


def generated_parts(robot: Robot, *, method: str = DEFAULT_METHOD,
                    package_paths: Sequence[str] = (),
                    package_map: Sequence[tuple[str, str]] = (),
                    **overrides: Any) -> Mapping[str, tuple[Any, ...]]:
    """New collision parts per link from `robotdesc.generate_collision` (link name -> parts).

    Links whose generation failed are left out (they keep their geometry as written).
    """

    result = generate_collision(robot, method, package_paths=package_paths,
                                package_map=package_map, **overrides)
    parts = {outcome.report.link: outcome.parts for outcome in result.outcomes
             if outcome.written}
    skipped = [o.report.link for o in result.outcomes if not o.written]
    if skipped:
        log.warning("collision generation failed for %d links (kept as written): %s",
                    len(skipped), ", ".join(skipped[:5]))
    return parts

