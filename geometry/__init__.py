"""Tooth-surface geometry and kinematics: pure numpy/scipy, imports nothing else of ours."""
