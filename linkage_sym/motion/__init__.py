"""The motion of a machine driven by its motor: equations of motion, simulation, flywheel.

* :mod:`~linkage_sym.motion.equations`: the equation of motion of a mechanism of one
  degree of freedom, ``J qdd + J' qd^2 / 2 = M_motor(qd) - Q``, its ``J`` from the derived
  equations and its forces from the kinetostatic solver;
* :mod:`~linkage_sym.motion.integrate`: its integration (SciPy's stiff-capable solvers,
  dense output, events for a stall and a state that cannot be solved);
* :mod:`~linkage_sym.motion.pieces`: the breakpoints of the equation (the motor table's
  rows, the loads' switch points), at which the integration restarts, and the equation
  frozen on each smooth piece between them;
* :mod:`~linkage_sym.motion.simulate`: ``simulate`` (the contract's result: the steps at
  the sampled times, analysed as ``analyze`` analyses them, and the periodic ``motion``);
* :mod:`~linkage_sym.motion.periodic`: the periodic regime, its mean speed and fluctuation;
* :mod:`~linkage_sym.motion.flywheel`: the flywheel a requested fluctuation needs.
"""
