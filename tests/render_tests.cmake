# Tests of globular_render.
