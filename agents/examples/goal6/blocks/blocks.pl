% The blocks world: what is clear, what a tower is.
:- dynamic block/1, on/2.
clear(table).
clear(X) :- block(X), not(on(_, X)).
tower([X]) :- on(X, table).
tower([X, Y | T]) :- on(X, Y), tower([Y | T]).
