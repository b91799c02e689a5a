"""The test tree mirrors the package (``tests/geometry``, ``tests/fem``, ``tests/ltca``); shared fixtures live in
``tests/fixtures`` and are registered here. Tiers (pyproject.toml): the default suite, ``-m heavy`` (the large
models and full comparisons, run by CI) and ``-m slow`` (long validations, run by hand)."""
pytest_plugins = ["fixtures.cylindrical", "fixtures.bevel", "fixtures.meshes"]
