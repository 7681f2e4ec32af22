# The simulator links a bench subsystem: must fail check_layers.cmake.
set(HOILCD_TARGETS "hoilcd_sim_output;hoilcd_bench_evaluation")
set(HOILCD_LINKS_hoilcd_sim_output "hoilcd_bench_evaluation")
set(HOILCD_LINKS_hoilcd_bench_evaluation "")
