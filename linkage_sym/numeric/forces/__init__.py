"""Forces: the kinetostatics of a solved sweep (NumPy/SciPy only).

``loads`` (applied and inertia wrenches), ``statics`` (input and dyad
routines), ``superposition`` (Dang and Zhang's disconnection and
superposition), ``global_statics`` (every link at once: the check),
``kinetostatics`` (the force plan: one ``ForceRoutine`` per group).
"""
