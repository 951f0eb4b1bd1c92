:- dynamic started/1, done/1, skipped/1.
