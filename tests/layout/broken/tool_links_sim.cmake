# The Python dataset bindings link the simulator to read a dataset: must fail check_layers.cmake.
set(HOILCD_TARGETS "hoilcd_python_dataset;hoilcd_core_dataset;hoilcd_sim_output")
set(HOILCD_LINKS_hoilcd_python_dataset "hoilcd_core_dataset;hoilcd_sim_output")
set(HOILCD_LINKS_hoilcd_core_dataset "")
set(HOILCD_LINKS_hoilcd_sim_output "")
