on(a, b), on(b, c), on(c, table).
