# core's matching reaches the simulator through features: must fail check_layers.cmake.
set(HOILCD_TARGETS "hoilcd_core_matching;hoilcd_core_features;hoilcd_sim_scene")
set(HOILCD_LINKS_hoilcd_core_matching "hoilcd_core_features")
set(HOILCD_LINKS_hoilcd_core_features "hoilcd_sim_scene")
set(HOILCD_LINKS_hoilcd_sim_scene "")
