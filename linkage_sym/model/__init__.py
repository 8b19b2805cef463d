"""Plain data: the scene classes every layer reads. No computation here."""

from linkage_sym.model.scene import (
    GROUND,
    OUTPUTS,
    STAGES,
    CamSpec,
    Driver,
    Effects,
    Joint,
    JointFriction,
    Link,
    Load,
    LoadTable,
    Motor,
    Scene,
    Simulation,
    Spring,
    TracedPoint,
)

__all__ = ["GROUND", "OUTPUTS", "STAGES", "CamSpec", "Driver", "Effects", "Joint", "JointFriction", "Link", "Load",
           "LoadTable", "Motor", "Scene", "Simulation", "Spring", "TracedPoint"]
