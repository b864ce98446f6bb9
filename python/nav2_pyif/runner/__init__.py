"""The offline runner: a planner host, a map and a simulated robot, no ROS or Nav2 needed."""
