"""Face-milled spiral bevel gears: blank, head cutter, cradle machine, generation, synthesis."""
