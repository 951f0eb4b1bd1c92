:- dynamic block/1, on/2, holding/1.
clear(table).
clear(X) :- block(X), \+ on(_, X), \+ holding(X).
above(X, Y) :- on(X, Y).
above(X, Y) :- on(X, Z), above(Z, Y).
tower([X]) :- on(X, table).
tower([X, Y | T]) :- on(X, Y), tower([Y | T]).
