on(b7, b6), on(b6, b5), on(b5, b4), on(b4, table), on(b3, b2), on(b2, b1), on(b1, table).
