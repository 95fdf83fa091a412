# Tests of globular_surface.
