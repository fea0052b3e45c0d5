# What `cmake --install` puts under CMAKE_INSTALL_PREFIX: the layout of the images and of the
# systemd units (/opt/ltm: programs in bin/, launch configs in launch_configs/). Only what a robot
# or a base station runs: no tests, no benchmarks, no sources.
#   cmake --build build --target ltm_host ltm_eval ltm_mcap ltm_site ltm_sim
#   cmake --install build --prefix /opt/ltm
set(LTM_INSTALL_PROGRAMS
    ltm_host   # every launch config: the robot's, the base station's, the tools'
    ltm_eval   # report.html of a run, trajectory and map evaluation
    ltm_mcap   # ./ltm info, record --recover
    ltm_site   # ./ltm map versions|check|import|anchor
    ltm_sim)   # simulated runs in KITTI layout
install(TARGETS ${LTM_INSTALL_PROGRAMS} RUNTIME DESTINATION bin)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/launch_configs/ DESTINATION launch_configs
        PATTERN "*.sh" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                                   WORLD_READ WORLD_EXECUTE)
# The simulator's scenarios (LTM_SCENARIO of robot_composed.yaml and the simulated robots) and the
# three KITTI 00 scans of the tests (LTM_DATA of robot.yaml and kitti_composed.yaml): a run works
# out of the box, a site mounts its own data over them.
install(DIRECTORY ${CMAKE_SOURCE_DIR}/components/simulator/scenarios/ DESTINATION scenarios
        FILES_MATCHING PATTERN "*.yaml")
install(DIRECTORY ${CMAKE_SOURCE_DIR}/tests/fixtures/kitti00_mini DESTINATION data)
