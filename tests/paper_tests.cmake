# Tests of globular_paper: the table metrics and verdict rules, and a reduced-size run of
# `globular figures`.
globular_test(outcome_metrics_test SOURCES outcome_metrics_test.cpp LIBS globular_paper)
globular_test(figures_test SOURCES figures_test.cpp LIBS globular_paper)
add_dependencies(figures_test globular)
