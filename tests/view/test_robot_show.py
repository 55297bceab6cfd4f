"""`Robot.show()` gives the same view as `robotdesc.show(robot)`."""

from __future__ import annotations

from robotdesc.model.parse import parse_urdf

URDF = b"""<robot name="two">
  <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual></link>
  <link name="arm"><visual><geometry><cylinder radius="0.02" length="0.3"/></geometry></visual></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def test_robot_show_renders_its_links(tmp_path):
    robot = parse_urdf(URDF, str(tmp_path / "two.urdf"))
    view = robot.show({"j": 0.5})
    html = view._repr_html_()
    assert "iframe" in html and "arm" in view.html()
