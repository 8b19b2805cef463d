"""Forces: the kinetostatics of a solved sweep (NumPy/SciPy only).

``loads`` (applied and inertia wrenches), ``statics`` (input and dyad
routines), ``superposition`` (Dang and Zhang's disconnection and
superposition), ``global_statics`` (every link at once: the check),
``friction`` (joint friction: each group's Newton around its linear routine, the
self-locking criterion), ``global_friction`` (the global method's own nonlinear solve
with friction), ``kinetostatics`` (the force plan: one ``ForceRoutine`` per group).
"""
