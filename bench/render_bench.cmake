# Benchmarks of globular_render.
