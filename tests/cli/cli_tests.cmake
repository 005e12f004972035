# The command line's exit statuses (README "Command line"): 0 success, 1 the task failed, 2 bad
# usage or input, naming the option or file. Included from tests/CMakeLists.txt when the CLI is built.
set(_cli_dir ${CMAKE_CURRENT_SOURCE_DIR}/cli)
set(_cli_out ${CMAKE_CURRENT_BINARY_DIR}/cli_out)
set(_data ${CMAKE_CURRENT_SOURCE_DIR}/data)
set(_maze ${_data}/teb_tutorials/maps/maze.yaml)
set(_cloud ${_data}/pcl/sac_plane_test.pcd)
set(_pair ${_data}/lidar/fast_gicp)
set(_gradient ${_data}/heightmaps/grid_map/linearGradient_horizontal.png)
set(_t3_world ${PROJECT_SOURCE_DIR}/scenarios/worlds/turtlebot3/worlds/turtlebot3_world.world)

# bipednav_cli(NAME STATUS REGEX ARG...): `bipednav ARG...` exits with STATUS, its output matching REGEX.
function(bipednav_cli name status regex)
  add_test(NAME cli_${name} COMMAND sh ${_cli_dir}/expect_exit.sh ${status} "${regex}" $<TARGET_FILE:bipednav> ${ARGN})
  set_tests_properties(cli_${name} PROPERTIES TIMEOUT 300 LABELS cli)
endfunction()

# Per command: a success (0), a task failure (1) where the command has a task that can fail, and a
# usage or input error (2).
bipednav_cli(run_success 0 ": SUCCESS \\(goal reached at t = " run hexagon_static --quiet --out ${_cli_out}/run)
bipednav_cli(run_task_failed 1 "FAILED \\(PAT_EXCEEDED" run hexagon_static --time-limit 2 --out ${_cli_out}/run_short)
bipednav_cli(run_bad_number 2 "--time-limit: expected a finite number > 0, got '-5'" run hexagon_static --time-limit -5)
bipednav_cli(run_negative_seed 2 "--seed: expected a whole number >= 0" run hexagon_static --seed -1)
bipednav_cli(run_world_needs_start 2 "--world requires --start" run --world ${_t3_world} --goal 1,1)
bipednav_cli(run_goal_in_obstacle 2 "the goal \\(0.00, 0.00\\) is inside 'turtlebot3_world::" run --world ${_t3_world}
             --start -2,-0.5 --goal 0,0 --out ${_cli_out}/run_world)
bipednav_cli(run_unwritable_out 2 "--out /proc/bipednav: cannot create the directory" run hexagon_static --out /proc/bipednav)
# open_field: 8 m of open floor after the posts, where LOAM's map match observes neither x nor y:
# the navigator's SUCCESS says that its estimate is weak along the way it came (sigma 0.18 m), and
# the planners aim inside the tolerance minus twice that, so the true pose ends inside it on 9 of
# 10 seeds (bench/results/scenarios_open_field.json; seed 1 ends 2 mm outside).
bipednav_cli(run_weak_estimate_reported 0 "navigator: goal reached; the position estimate is weak along the direction of travel"
             run open_field --seed 2 --quiet --out ${_cli_out}/run_open_field)
bipednav_cli(run_footsteps_success 0 "SUCCESS \\(SUCCESS" run nao_stairs --out ${_cli_out}/run_nao)
bipednav_cli(run_footsteps_task_failed 1 "FAILED \\(PAT_EXCEEDED" run nao_stairs --time-limit 2 --out ${_cli_out}/run_nao_short)
bipednav_cli(params_success 0 "^# bipednav navigation parameters" params)
bipednav_cli(params_no_machine_path 0 "# behavior_tree: the built-in config/behavior_trees/navigate.xml" params)
bipednav_cli(params_humanoid_layout 2 "reads the footstep navigator's layout"
             params --robot nao --params ${_data}/navigator_params/override.yaml)
bipednav_cli(sim_success 0 "1.0 s simulated" sim hexagon_static --duration 1 --quiet --out ${_cli_out}/sim)
bipednav_cli(sim_bad_scenario 2 "no scenario 'no_such_scenario'" sim no_such_scenario)
# odometry's default route on a scenario: the widest route around the prism between three_rooms'
# start and goal, driven to its end without contact.
bipednav_cli(odometry_route_completed 0 "\"route_completed\": true" odometry three_rooms --json)
bipednav_cli(odometry_route_no_contact 0 "\"contacts\": 0," odometry three_rooms --json)
bipednav_cli(route_success 0 "margin \\+0.348 m" route hexagon_static)
bipednav_cli(route_task_failed 1 "no route" route --world ${_t3_world} --start -2,-0.5 --goal 0,0)
bipednav_cli(route_world_needs_start 2 "--world requires --start" route --world ${_t3_world} --goal 1,1)
bipednav_cli(cloud_filter_success 0 "3283 points, 3283 after the pass-through, 2426 after the voxel grid"
             cloud filter ${_cloud} ${_cli_out}/filtered.pcd --voxel 0.02)
bipednav_cli(cloud_filter_bad_band 2 "--zmin: expected a number <= --zmax"
             cloud filter ${_cloud} ${_cli_out}/filtered.pcd --zmin 1 --zmax 0)
bipednav_cli(cloud_segment_success 0 "2512 of 3283 points within 0.030 m" cloud segment ${_cloud})
bipednav_cli(cloud_segment_task_failed 1 "no plane found" cloud segment ${_cloud} --zmin 100)
bipednav_cli(cloud_segment_bad_probability 2 "--probability: expected a finite number in \\(0, 1\\)"
             cloud segment ${_cloud} --probability 1)
bipednav_cli(costmap_info_success 0 "\"width_cells\": 200" costmap info ${_maze})
bipednav_cli(costmap_info_image 2 "a PNG image, not a map_server YAML" costmap info ${_data}/teb_tutorials/maps/maze.png)
bipednav_cli(costmap_inflate_success 0 "\"inscribed\"" costmap inflate ${_maze} --inscribed-radius 0.2 --inflation-radius 0.5
             --cost-scaling 2 --out ${_cli_out}/inflated.png)
bipednav_cli(costmap_inflate_bad_radii 2 "--inflation-radius: expected >= --inscribed-radius"
             costmap inflate ${_maze} --inscribed-radius 0.3 --inflation-radius 0.1)
bipednav_cli(costmap_inflate_old_flag 2 "--inscribed" costmap inflate ${_maze} --inscribed 0.3)
bipednav_cli(plan_grid_success 0 "^SUCCESS \\(dstar_lite\\)" plan grid ${_maze} --start 1,1 --goal 8,8 --out ${_cli_out}/plan.png)
bipednav_cli(plan_grid_blocked_goal 1 "^BLOCKED_GOAL" plan grid ${_maze} --start 1,1 --goal 0.02,5)
bipednav_cli(plan_grid_off_the_map 1 "^OUT_OF_MAP" plan grid ${_maze} --start 1,1 --goal 20,5)
bipednav_cli(plan_grid_bad_pose 2 "--goal: expected x,y or x,y,yaw" plan grid ${_maze} --start 1,1 --goal 8)
bipednav_cli(plan_movingai_success 0 "160/160 rows solved"
             plan movingai ${_data}/movingai/maps/arena.map ${_data}/movingai/scen/arena.map.scen)
bipednav_cli(plan_movingai_missing_file 2 "scen: File does not exist" plan movingai ${_data}/movingai/maps/arena.map no.scen)
# walled.map: a wall splits the 5 x 3 map; the second row's goal is behind it.
bipednav_cli(plan_movingai_task_failed 1 "1/2 rows solved" plan movingai ${_cli_dir}/data/walled.map
             ${_cli_dir}/data/walled.map.scen)
bipednav_cli(local_plan_success 0 "\"reached\": true" local plan ${_maze} --start 1,1 --goal 8,8 --out ${_cli_out}/local.png)
bipednav_cli(local_plan_task_failed 1 "\"reached\": false" local plan ${_maze} --start 1,1 --goal 8,8 --steps 5)
bipednav_cli(local_plan_bad_planner 2 "--planner: teb2 not in" local plan ${_maze} --start 1,1 --goal 8,8 --planner teb2)
bipednav_cli(register_success 0 "converged after" register ${_pair}/251370668.pcd ${_pair}/251371071.pcd)
# From identity GICP finds no correspondence between the table scene (a stereo camera's view) and the LiDAR scan.
bipednav_cli(register_task_failed 1 "NOT converged" register ${_data}/pcl/table_scene_mug_stereo_textured.pcd
             ${_pair}/251370668.pcd)
bipednav_cli(register_bad_threads 2 "--threads: expected a whole number in \\[1, 256\\]"
             register ${_pair}/251370668.pcd ${_pair}/251371071.pcd --threads 0)
bipednav_cli(footsteps_success 0 "^SUCCESS: footstep plan" footsteps ${_gradient} --start 1,1 --goal 2.5,1.5
             --min-height -0.01 --max-height 0 --out ${_cli_out}/footsteps.png)
bipednav_cli(footsteps_task_failed 1 "^BLOCKED_GOAL" footsteps ${_gradient} --start 0.3,0.5 --goal 1.5,0.5
             --out ${_cli_out}/footsteps_failed.png)
bipednav_cli(footsteps_map_server_yaml 2 "this is a map_server occupancy map" footsteps ${_maze} --start 1,1 --goal 2,2
             --out ${_cli_out}/footsteps_maze.png)
bipednav_cli(bench_local_bad_cycles 2 "--cycles: expected a whole number >= 1" bench local --cycles 0)
bipednav_cli(bench_local_robot_settings 0 "\"teb_settings\": \"robot digit\"" bench local --robot digit --cycles 2)
bipednav_cli(bench_scenarios_humanoid 0 "\"as_expected\": 1," bench scenarios --scenarios nao_stairs --robots nao --seeds 1 --json)

# Every numeric option fed a negative number, NaN and zero (numeric_flag.sh): NaN always exits 2
# naming the option; the table gives the status for -1 and for 0 (0 or 1 where the value is valid).
# bipednav_numeric(NAME FLAG NEGATIVE_STATUS ZERO_STATUS ARG...): ARG... is a command that runs (fast) as given.
function(bipednav_numeric name flag negative zero)
  add_test(NAME cli_numeric_${name} COMMAND sh ${_cli_dir}/numeric_flag.sh ${flag} ${negative} ${zero}
                                            $<TARGET_FILE:bipednav> ${ARGN})
  set_tests_properties(cli_numeric_${name} PROPERTIES TIMEOUT 300 LABELS cli)
endfunction()
#               test name                 flag            -1 0  command
bipednav_numeric(run_seed                  --seed             2 1  run hexagon_static --time-limit 0.5 --out ${_cli_out}/num_run)  # 0 is a seed; the run times out
bipednav_numeric(run_time_limit            --time-limit       2 2  run hexagon_static --out ${_cli_out}/num_run)
bipednav_numeric(sim_duration              --duration         2 2  sim hexagon_static --out ${_cli_out}/num_sim)
bipednav_numeric(sim_step                  --step             2 2  sim hexagon_static --out ${_cli_out}/num_sim)
bipednav_numeric(route_resolution          --resolution       2 2  route hexagon_static)
bipednav_numeric(cloud_filter_voxel        --voxel            2 0  cloud filter ${_cloud} ${_cli_out}/num.pcd)  # 0: no voxel grid
bipednav_numeric(cloud_filter_range        --range            2 2  cloud filter ${_cloud} ${_cli_out}/num.pcd)
bipednav_numeric(cloud_filter_zmin         --zmin             0 0  cloud filter ${_cloud} ${_cli_out}/num.pcd)  # heights may be negative
bipednav_numeric(cloud_filter_zmax         --zmax             0 0  cloud filter ${_cloud} ${_cli_out}/num.pcd)
bipednav_numeric(cloud_segment_threshold   --threshold        2 2  cloud segment ${_cloud})
bipednav_numeric(cloud_segment_probability --probability      2 2  cloud segment ${_cloud})
bipednav_numeric(cloud_segment_max_iterations --max-iterations   2 2  cloud segment ${_cloud})
bipednav_numeric(cloud_segment_seed        --seed             2 0  cloud segment ${_cloud})  # 0 is a seed
bipednav_numeric(costmap_inflate_inscribed_radius --inscribed-radius 2 0  costmap inflate ${_maze})  # a point robot
bipednav_numeric(costmap_inflate_inflation_radius --inflation-radius 2 2  costmap inflate ${_maze})  # 0 < the inscribed radius 0.2
bipednav_numeric(costmap_inflate_cost_scaling --cost-scaling     2 0  costmap inflate ${_maze})  # 0: flat inflation
bipednav_numeric(costmap_inflate_scale     --scale            2 2  costmap inflate ${_maze} --out ${_cli_out}/num.png)
bipednav_numeric(plan_grid_inscribed_radius --inscribed-radius 2 0  plan grid ${_maze} --start 1,1 --goal 8,8)
bipednav_numeric(plan_grid_inflation_radius --inflation-radius 2 2  plan grid ${_maze} --start 1,1 --goal 8,8)
bipednav_numeric(plan_grid_cost_scaling    --cost-scaling     2 0  plan grid ${_maze} --start 1,1 --goal 8,8)
bipednav_numeric(plan_grid_cost_weight     --cost-weight      2 0  plan grid ${_maze} --start 1,1 --goal 8,8)  # 0: shortest path
bipednav_numeric(local_plan_steps          --steps            2 2  local plan ${_maze} --start 1,1 --goal 8,8)
bipednav_numeric(local_plan_threads        --threads          2 2  local plan ${_maze} --start 1,1 --goal 8,8 --steps 1)
bipednav_numeric(register_voxel            --voxel            2 0  register ${_pair}/251370668.pcd ${_pair}/251371071.pcd)  # 0: no down-sampling
bipednav_numeric(register_threads          --threads          2 2  register ${_pair}/251370668.pcd ${_pair}/251371071.pcd)
bipednav_numeric(footsteps_resolution      --resolution       2 2  footsteps ${_gradient} --start 1,1 --goal 2.5,1.5 --out ${_cli_out}/num_fs.png)
bipednav_numeric(footsteps_min_height      --min-height       1 1  footsteps ${_gradient} --start 1,1 --goal 2.5,1.5 --out ${_cli_out}/num_fs.png)  # valid; the slope is too steep
bipednav_numeric(footsteps_max_height      --max-height       2 1  footsteps ${_gradient} --start 1,1 --goal 2.5,1.5 --out ${_cli_out}/num_fs.png)  # -1 < --min-height -0.5
bipednav_numeric(footsteps_time_limit      --time-limit       2 2  footsteps ${_gradient} --start 1,1 --goal 2.5,1.5 --out ${_cli_out}/num_fs.png)
bipednav_numeric(bench_sim_duration       --duration         2 2  bench sim)
bipednav_numeric(bench_perception_reps    --reps             2 2  bench perception)
bipednav_numeric(bench_mapping_iterations --iterations       2 2  bench mapping)
bipednav_numeric(bench_global_max_replans --max-replans      2 2  bench global)
bipednav_numeric(bench_local_cycles       --cycles           2 2  bench local)
bipednav_numeric(bench_local_threads      --threads          2 2  bench local)
bipednav_numeric(bench_footsteps_maps     --maps             2 2  bench footsteps)
bipednav_numeric(bench_footsteps_problems --problems         2 2  bench footsteps)
bipednav_numeric(bench_footsteps_optimal_limit --optimal-limit    2 2  bench footsteps)
bipednav_numeric(bench_footsteps_short_limit --short-limit      2 2  bench footsteps)
bipednav_numeric(bench_footsteps_long_limit --long-limit       2 2  bench footsteps)
bipednav_numeric(bench_footsteps_jobs     --jobs             2 2  bench footsteps)
bipednav_numeric(run_goal_tolerance        --goal-tolerance   2 2  run hexagon_static --out ${_cli_out}/num_run)  # M,RAD: one number is not a pair
bipednav_numeric(odometry_duration         --duration         2 2  odometry three_rooms --json)
bipednav_numeric(odometry_speed            --speed            2 2  odometry three_rooms --json)
bipednav_numeric(odometry_max_sweeps       --max-sweeps       2 2  odometry ${_pair})
bipednav_numeric(odometry_map_voxel        --map-voxel        2 2  odometry ${_pair})
bipednav_numeric(odometry_gicp_voxel       --gicp-voxel       2 2  odometry ${_pair} --method gicp)
bipednav_numeric(odometry_rpe_distance     --rpe-distance     2 2  odometry ${_pair})
# More benchmarks (BENCH:FLAG): -1, NaN and 0 are all rejected before any work (exit 2).
foreach(_case scenarios:--seeds scenarios:--first-seed scenarios:--jobs loop:--runs worlds:--worlds
              worlds:--first-seed worlds:--jobs tracking:--seeds tracking:--first-seed tracking:--first-world
              localization:--sweeps)
  string(REPLACE ":" ";" _parts ${_case})
  list(GET _parts 0 _bench)
  list(GET _parts 1 _flag)
  string(REGEX REPLACE "^--" "" _id ${_flag})
  string(REPLACE "-" "_" _id ${_id})
  bipednav_numeric(bench_${_bench}_${_id} ${_flag} 2 2 bench ${_bench})
endforeach()

# The README's command-line examples run as written (readme_examples.sh).
add_test(NAME cli_readme_examples COMMAND sh ${_cli_dir}/readme_examples.sh ${PROJECT_SOURCE_DIR} $<TARGET_FILE:bipednav>
                                          ${CMAKE_CURRENT_BINARY_DIR}/cli_readme)
set_tests_properties(cli_readme_examples PROPERTIES TIMEOUT 600 LABELS cli)

# --json on every command that prints figures (expect_json.py): exactly one JSON object on stdout
# with the expected keys and the command's exit status; a usage error prints nothing on stdout.
# bipednav_json(NAME STATUS KEYS ARG...): KEYS comma-separated, nested keys joined by dots.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  function(bipednav_json name status keys)
    add_test(NAME cli_json_${name} COMMAND ${Python3_EXECUTABLE} ${_cli_dir}/expect_json.py ${status} "${keys}"
                                           $<TARGET_FILE:bipednav> ${ARGN})
    set_tests_properties(cli_json_${name} PROPERTIES TIMEOUT 300 LABELS cli)
  endfunction()
  bipednav_json(run_task_failed 1 "success,verdict,navigator_outcome,goal_error_m,outputs.run_json,outputs.run_png"
                run hexagon_static --time-limit 2 --quiet --json --out ${_cli_out}/json_run)
  bipednav_json(run_footsteps_task_failed 1 "success,navigator_outcome,seed,verdict,final_true_pose,steps,goal_error_m,outputs.run_json"
                run nao_stairs --time-limit 2 --quiet --json --out ${_cli_out}/json_run_nao)
  bipednav_json(run_bad_number 2 "" run hexagon_static --json --time-limit -5)
  bipednav_json(sim_success 0 "duration_s,distance_m,collision_count,final_pose.x_m,outputs.sim_json"
                sim hexagon_static --duration 1 --quiet --json --out ${_cli_out}/json_sim)
  bipednav_json(sim_bad_scenario 2 "" sim no_such_scenario --json)
  bipednav_json(route_success 0 "routes" route hexagon_static --json)
  bipednav_json(route_task_failed 1 "routes" route --world ${_t3_world} --start -2,-0.5 --goal 0,0 --json)
  bipednav_json(plan_grid_success 0 "outcome,length_m,poses,expansions,time_ms,path,png"
                plan grid ${_maze} --start 1,1 --goal 8,8 --json --out ${_cli_out}/json_plan.png)
  bipednav_json(plan_grid_blocked_goal 1 "outcome,message,path" plan grid ${_maze} --start 1,1 --goal 0.02,5 --json)
  bipednav_json(plan_grid_bad_pose 2 "" plan grid ${_maze} --start 1,1 --goal 8 --json)
  bipednav_json(plan_movingai_success 0 "rows,summary.solved,summary.max_abs_error_cells,summary.total_time_ms"
                plan movingai ${_data}/movingai/maps/arena.map ${_data}/movingai/scen/arena.map.scen --json)
  bipednav_json(local_plan_success 0 "reached,last_outcome,cycles,time_s,final_pose.yaw_rad,global_plan.length_m"
                local plan ${_maze} --start 1,1 --goal 8,8 --json)
  bipednav_json(local_plan_task_failed 1 "reached,last_outcome" local plan ${_maze} --start 1,1 --goal 8,8 --steps 5 --json)
  bipednav_json(costmap_info_success 0 "geometry.width_cells,geometry.resolution_m,costs.lethal" costmap info ${_maze} --json)
  bipednav_json(costmap_inflate_success 0 "geometry,inflate_ms,costs.inscribed" costmap inflate ${_maze} --json)
  bipednav_json(footsteps_success 0 "outcome,steps,walking_s,expansions,png" footsteps ${_gradient} --start 1,1
                --goal 2.5,1.5 --min-height -0.01 --max-height 0 --json --out ${_cli_out}/json_footsteps.png)
  bipednav_json(footsteps_task_failed 1 "outcome,message,steps" footsteps ${_gradient} --start 0.3,0.5 --goal 1.5,0.5
                --json --out ${_cli_out}/json_footsteps_failed.png)
  bipednav_json(cloud_filter_success 0 "points,after_pass_through,after_voxel_grid,voxel_m,time_ms,out"
                cloud filter ${_cloud} ${_cli_out}/json_filtered.pcd --voxel 0.02 --json)
  bipednav_json(cloud_filter_bad_band 2 "" cloud filter ${_cloud} ${_cli_out}/json_filtered.pcd --zmin 1 --zmax 0 --json)
  bipednav_json(cloud_segment_success 0 "found,plane,inliers,points,time_ms" cloud segment ${_cloud} --json)
  bipednav_json(cloud_segment_task_failed 1 "found,points" cloud segment ${_cloud} --zmin 100 --json)
  bipednav_json(plan_movingai_task_failed 1 "rows,summary.solved" plan movingai ${_cli_dir}/data/walled.map
                ${_cli_dir}/data/walled.map.scen --json)
  bipednav_json(register_task_failed 1 "converged,correspondences" register
                ${_data}/pcl/table_scene_mug_stereo_textured.pcd ${_pair}/251370668.pcd --json)
  bipednav_json(register_success 0 "T_target_source,converged,fitness,time_ms"
                register ${_pair}/251370668.pcd ${_pair}/251371071.pcd --json)
else()
  message(STATUS "bipednav: python3 not found, the cli_json_* tests (one JSON object per --json) are not run")
endif()
