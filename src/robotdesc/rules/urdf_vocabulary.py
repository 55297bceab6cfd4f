"""The URDF vocabulary: one table of the elements and attributes URDF defines, and of the
extensions real descriptions use.

The URDF part follows the URDF XML specification as urdfdom's parser reads it
(urdf_parser/src/{model,link,joint,pose}.cpp): robot, link, inertial, visual, collision,
geometry and its shapes, material, joint and its children. `capsule` is read by robotdesc's
model (and by some consumers) though urdfdom does not define it.

Extensions are listed with the tool that reads them. An extension element is free-form: its
contents are never judged (gazebo, transmission, ros2_control, sensor, ...). Elements and
attributes in an XML namespace (`xacro:*`, `drake:*`) are not URDF's business either.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class ElementSpec:
    """What URDF defines for one element.

    Attributes:
        attributes: the attributes URDF defines on it.
        children: the child elements URDF defines in it.
        extension_attributes: attributes known extensions add (name -> who reads them).
        extension_children: child elements known extensions add (name -> who reads them);
            their contents are not judged.
        judge_children: whether unknown children are reported (False where another rule
            already reports them, e.g. an unknown shape in `<geometry>`).
    """

    attributes: frozenset[str] = frozenset()
    children: frozenset[str] = frozenset()
    extension_attributes: tuple[tuple[str, str], ...] = ()
    extension_children: tuple[tuple[str, str], ...] = ()
    judge_children: bool = True

    def known_attribute(self, name: str) -> bool:
        return name in self.attributes or any(name == n for n, _ in self.extension_attributes)

    def known_child(self, name: str) -> bool:
        return name in self.children or any(name == n for n, _ in self.extension_children)


def _spec(attributes: str = "", children: str = "", *,
          extension_attributes: tuple[tuple[str, str], ...] = (),
          extension_children: tuple[tuple[str, str], ...] = (),
          judge_children: bool = True) -> ElementSpec:
    return ElementSpec(frozenset(attributes.split()), frozenset(children.split()),
                       tuple(extension_attributes), tuple(extension_children), judge_children)


_ROBOT_EXTENSIONS = (
    ("gazebo", "Gazebo (URDF->SDF extension blocks)"),
    ("transmission", "ros_control / ros2_control"),
    ("ros2_control", "ros2_control"),
    ("mujoco", "MuJoCo's URDF compiler"),
    ("sensor", "urdfdom's sensor parser (urdf_sensor)"),
    ("webots", "webots_ros2"),
    ("klampt", "Klampt"),
)

#: The table: element name -> what it may hold. An element missing here is not judged
#: (its parent's spec decides whether it may appear at all).
URDF_ELEMENTS: dict[str, ElementSpec] = {
    "robot": _spec("name version", "link joint material", extension_children=_ROBOT_EXTENSIONS),
    "link": _spec("name", "inertial visual collision", extension_attributes=(
        ("type", "PR2-era sensor links (ignored by every consumer)"),
    ), extension_children=(
        ("contact", "pybullet (lateral_friction, restitution, ...)"),
        ("self_filter", "robot_self_filter"),
        ("collision_checking", "PR2-era collision capsules (urdfdom 0.x)"),
    )),
    "inertial": _spec("", "origin mass inertia"),
    "origin": _spec("xyz rpy"),
    "mass": _spec("value"),
    "inertia": _spec("ixx ixy ixz iyy iyz izz"),
    "visual": _spec("name", "origin geometry material"),
    "collision": _spec("name", "origin geometry", extension_children=(
        ("verbose", "PR2-era collision debugging"),
        ("material", "exporters that copy the visual (ignored by every consumer)"),
    )),
    "geometry": _spec("", "box cylinder sphere mesh capsule", extension_attributes=(
        ("name", "exporters (ignored)"),
    ), judge_children=False),  # an unknown shape is S110's
    "box": _spec("size"),
    "cylinder": _spec("radius length"),
    "sphere": _spec("radius"),
    "capsule": _spec("radius length"),
    "mesh": _spec("filename scale"),
    "material": _spec("name", "color texture"),
    "color": _spec("rgba"),
    "texture": _spec("filename"),
    "joint": _spec("name type", "origin parent child axis limit dynamics mimic "
                   "safety_controller calibration", extension_attributes=(
                       ("dont_collapse", "Isaac Sim's URDF importer"),
                   )),
    "parent": _spec("link"),
    "child": _spec("link"),
    "axis": _spec("xyz"),
    "limit": _spec("lower upper effort velocity", extension_attributes=(
        ("current", "ANYbotics descriptions"),
        ("command_effort", "ANYbotics descriptions"),
        ("gear_velocity", "ANYbotics descriptions"),
    )),
    "dynamics": _spec("damping friction", extension_attributes=(
        ("K", "franka_description (Franka's own simulation)"),
        ("D", "franka_description"),
        ("mu_coulomb", "franka_description"),
        ("mu_viscous", "franka_description"),
    )),
    "mimic": _spec("joint multiplier offset"),
    "safety_controller": _spec("soft_lower_limit soft_upper_limit k_position k_velocity"),
    "calibration": _spec("rising falling", extension_attributes=(
        ("reference_position", "PR2 calibration"),
    )),
}

#: Tags that Gazebo reads inside `<gazebo reference=...>` and that are often written
#: directly in a link or joint, where nothing reads them.
GAZEBO_TAGS = frozenset({
    "gravity", "kinematic", "selfCollide", "self_collide", "mu1", "mu2", "kp", "kd", "fdir1",
    "maxVel", "minDepth", "maxContacts", "turnGravityOff", "provideFeedback",
    "implicitSpringDamper", "stopKp", "stopKd", "stopCfm", "stopErp", "laserRetro",
    "dampingFactor", "surface", "enable_wind", "velocity_decay", "springReference",
    "springStiffness", "preserveFixedJoint", "disableFixedJointLumping", "cfmDamping",
})


#: Elements of early URDF that today's parsers ignore, by (parent, tag): the element that
#: replaced each, and that element's defaults (a legacy element that only restates them
#: loses nothing: S201 leaves it alone).
LEGACY_ELEMENTS: dict[tuple[str, str], tuple[str, dict[str, float]]] = {
    ("joint", "joint_properties"): ("dynamics", {"damping": 0.0, "friction": 0.0}),
}


def spec_of(tag: str) -> ElementSpec | None:
    """The spec of an element URDF defines, or None."""
    return URDF_ELEMENTS.get(tag)


def parents_of(tag: str) -> list[str]:
    """The elements in which URDF defines `tag` as a child, sorted."""
    return sorted(name for name, spec in URDF_ELEMENTS.items() if tag in spec.children)
