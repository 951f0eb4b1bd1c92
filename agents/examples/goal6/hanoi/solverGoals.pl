solved.
