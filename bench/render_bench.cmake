# Benchmarks of globular_render (not part of ctest; docs/render.md has the figures).
add_executable(render_bench render_bench.cpp)
target_link_libraries(render_bench PRIVATE globular_allocator globular_render benchmark::benchmark)
