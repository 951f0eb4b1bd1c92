% module_layout.pl: a pure-Prolog model of issue 29's per-agent slowdown (bench/README.md).
% N modules each hold the reference agent's beliefs; one round runs the reference agent's
% logic (bench/reference_floor.pl's rules) once in every module, round-robin, with the code
% laid out one of three ways. `own`: every module has its own copy of all of it; `shared`:
% one copy takes the module and calls M:Goal; `conditions`: as goalagent has it, the rules'
% conditions copied into each module and the rest (the loop over instantiations, the
% updates) shared. Prints the CPU µs per module-round after two untimed rounds:
%     swipl bench/module_layout.pl own|shared|conditions 1000
setup_module(M, own) :-
    forall(member(P, [cycle/1, sum/1, flag/1, reading/2, weight/2, high/1, goal/1]), dynamic(M:P)),
    reset(M),
    forall(own_clause(C), assertz(M:C)).
setup_module(M, shared) :-
    forall(member(P, [cycle/1, sum/1, flag/1, reading/2, weight/2, high/1, goal/1]), dynamic(M:P)),
    reset(M),
    assertz(M:toggle(on, off)), assertz(M:toggle(off, on)),
    assertz(M:(threshold(C, T) :- T is C mod 10)).
setup_module(M, conditions) :-
    setup_module(M, shared),
    forall(condition_clause(C), assertz(M:C)).
reset(M) :-
    assertz(M:cycle(0)), assertz(M:sum(0)), assertz(M:flag(off)),
    forall(nth0(I, [3, 7, 1, 9, 4, 0, 8, 2, 6, 5], V), assertz(M:reading(I, V))),
    forall(nth0(K, [2, 3, 5, 7, 11, 13, 17], W), assertz(M:weight(K, W))),
    assertz(M:goal(checkpoint(10))).
own_clause(toggle(on, off)).
own_clause(toggle(off, on)).
own_clause((threshold(C, T) :- T is C mod 10)).
own_clause((step :- event_high, event_low, count, accumulate, flip, move_checkpoint)).
own_clause((event_high :- forall(( cycle(C), threshold(C, T), reading(I, V), V > T, \+ high(I) ), assertz(high(I))))).
own_clause((event_low :- forall(( cycle(C), threshold(C, T), high(I), reading(I, V), V =< T ), retract(high(I))))).
own_clause((count :- ( cycle(C), Next is C + 1 -> retract(cycle(C)), assertz(cycle(Next)) ; true ))).
own_clause((accumulate :- ( cycle(C), K is C mod 7, weight(K, W), sum(S), New is (S + W * C) mod 1000003 -> retract(sum(S)), assertz(sum(New)) ; true ))).
own_clause((flip :- ( flag(F), toggle(F, G) -> retract(flag(F)), assertz(flag(G)) ; true ))).
own_clause((move_checkpoint :- ( goal(checkpoint(N)), cycle(C), C >= N, Later is C + 10 -> retract(goal(checkpoint(N))), assertz(goal(checkpoint(Later))) ; true ))).

condition_clause((c_high(C, T, I, V) :- cycle(C), threshold(C, T), reading(I, V), V > T, \+ high(I))).
condition_clause((c_low(C, T, I, V) :- cycle(C), threshold(C, T), high(I), reading(I, V), V =< T)).
condition_clause((c_count(C, Next) :- cycle(C), Next is C + 1)).
condition_clause((c_accumulate(C, K, W, S, New) :- cycle(C), K is C mod 7, weight(K, W), sum(S), New is (S + W * C) mod 1000003)).
condition_clause((c_flip(F, G) :- flag(F), toggle(F, G))).
condition_clause((c_move(N, C, Later) :- goal(checkpoint(N)), cycle(C), C >= N, Later is C + 10)).

cstep(M) :-
    forall(M:c_high(_, _, I, _), assertz(M:high(I))),
    forall(M:c_low(_, _, I, _), retract(M:high(I))),
    ( M:c_count(C, Next) -> retract(M:cycle(C)), assertz(M:cycle(Next)) ; true ),
    ( M:c_accumulate(_, _, _, S, New) -> retract(M:sum(S)), assertz(M:sum(New)) ; true ),
    ( M:c_flip(F, G) -> retract(M:flag(F)), assertz(M:flag(G)) ; true ),
    ( M:c_move(N, _, Later) -> retract(M:goal(checkpoint(N))), assertz(M:goal(checkpoint(Later))) ; true ).

sstep(M) :- s_event_high(M), s_event_low(M), s_count(M), s_accumulate(M), s_flip(M), s_move_checkpoint(M).
s_event_high(M) :- forall(( M:cycle(C), M:threshold(C, T), M:reading(I, V), V > T, \+ M:high(I) ), assertz(M:high(I))).
s_event_low(M) :- forall(( M:cycle(C), M:threshold(C, T), M:high(I), M:reading(I, V), V =< T ), retract(M:high(I))).
s_count(M) :- ( M:cycle(C), Next is C + 1 -> retract(M:cycle(C)), assertz(M:cycle(Next)) ; true ).
s_accumulate(M) :- ( M:cycle(C), K is C mod 7, M:weight(K, W), M:sum(S), New is (S + W * C) mod 1000003 -> retract(M:sum(S)), assertz(M:sum(New)) ; true ).
s_flip(M) :- ( M:flag(F), M:toggle(F, G) -> retract(M:flag(F)), assertz(M:flag(G)) ; true ).
s_move_checkpoint(M) :- ( M:goal(checkpoint(N)), M:cycle(C), C >= N, Later is C + 10 -> retract(M:goal(checkpoint(N))), assertz(M:goal(checkpoint(Later))) ; true ).

round(own, Ms) :- forall(member(M, Ms), M:step).
round(shared, Ms) :- forall(member(M, Ms), sstep(M)).
round(conditions, Ms) :- forall(member(M, Ms), cstep(M)).

measure(Kind, N, Us) :-
    numlist(1, N, Is),
    maplist([I, M]>>format(atom(M), "~w_~w_~w", [Kind, N, I]), Is, Ms),
    forall(member(M, Ms), setup_module(M, Kind)),
    round(Kind, Ms), round(Kind, Ms),
    Total is max(100000, N * 20), Rounds is Total // N,
    statistics(cputime, T0),
    forall(between(1, Rounds, _), round(Kind, Ms)),
    statistics(cputime, T1),
    Us is (T1 - T0) / (Rounds * N) * 1e6.

:- initialization(main, main).

main :-
    current_prolog_flag(argv, [Kind, Agents]),
    atom_number(Agents, N),
    measure(Kind, N, Micros),
    format("~w N=~w ~2f us~n", [Kind, N, Micros]).
