on(a, b), on(b, c), on(c, table), on(d, e), on(e, f), on(f, table).
