"""The numeric solver: kinematics, forces, Newton groups, continuation, accuracy, extremes."""
