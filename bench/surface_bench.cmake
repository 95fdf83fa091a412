# Benchmarks of globular_surface.
