% What the stacker knows of blocks: they are what sits on something; towers stand on the table.
:- dynamic on/2.
block(X) :- on(X, _).
clear(table).
clear(X) :- block(X), \+ on(_, X).
tower([X]) :- on(X, table).
tower([X, Y | T]) :- on(X, Y), tower([Y | T]).
