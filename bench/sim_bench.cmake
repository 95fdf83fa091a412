# Benchmarks of globular_sim.
