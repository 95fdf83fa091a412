# Tests of globular_sim.
