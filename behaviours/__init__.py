"""Sub-symbolic behaviours: camera perception, motor skills and affordance learners."""
