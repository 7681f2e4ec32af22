# The bench's report links the simulator: must fail check_layers.cmake (only the pipeline may).
set(HOILCD_TARGETS "hoilcd_bench_report;hoilcd_sim_sensor")
set(HOILCD_LINKS_hoilcd_bench_report "hoilcd_sim_sensor")
set(HOILCD_LINKS_hoilcd_sim_sensor "")
