"""Meshes, linear elasticity, compliance and contact. Imports `geometry` only."""
