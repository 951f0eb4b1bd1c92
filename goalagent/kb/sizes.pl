/*  What one built-in call of an agent may make: SWI-Prolog does some work in C without
    looking at signals, so neither the time limit nor Ctrl-C/SIGTERM (goalagent/kb/
    watchdog.py) can end it once it has begun. Measured on SWI-Prolog 9.0.4: X is 7^(10^9)
    takes 43 s in one inference; writing a 100,000,000-digit integer (format ~d, print/1)
    30 s; number_codes/2 of 10,000,000 digits more than 4 minutes; tab(2000000000) writes
    2 GB. So such work is bounded before it starts, as format/2,3's counts are (confine.pl):

    - integers: ^, ** and << in an agent's arithmetic may make at most max_integer_bits/1
      bits (an expression that contains them, or an is/2 expression holding a variable
      bound to anything but a number when it runs, is evaluated step by step, each power
      or shift checked before it is computed; a variable bound to a number costs is/2 one
      inline test; comparisons, which conditions make many of a cycle, are checked only
      when a power or shift is written in them); format/2,3 writes no integer larger;
    - tab/1,2 writes at most max_repeat/1 spaces (as format's counts);
    - a text an agent reads as a number or a term (number_codes/2, atom_to_term/3, ...)
      holds no run of more than max_digits/1 digits;
    - the runtime's print/1 and log/1 actions write at most max_print/1 characters (a term
      that shares subterms, f(T, T) nested 40 deep, writes 2^40 leaves in one call).

    confine.pl's prepare_call/3 asks sized/3 for every built-in call of an agent (loading
    its text, or when a goal built at run time is called); rules.pl asks printable/1.
*/
:- module(ga_sizes, []).

:- set_prolog_flag(generate_debug_info, false).

%!  max_integer_bits(-Bits) is det.
%   The largest integer (in bits) an agent's ^, ** or << may make, and format/2,3 may write:
%   writing one this big takes ~0.1 s (301,030 digits).
max_integer_bits(1000000).

%!  max_digits(-Count) is det.
%   The longest run of digits a text an agent reads as a number or term may hold.
max_digits(30000).

%!  max_repeat(-Count) is det.
%   The most characters tab/1,2 writes in one call (format's counts: confine.pl).
max_repeat(100000).

%!  max_print(-Characters) is det.
%   The longest text a print/1 or log/1 action writes.
max_print(1000000).

%!  sized(+G, +Ctx, -Sized) is semidet.
%   G (a built-in call of an agent, Ctx as confine.pl's) is one whose size is bounded
%   here; Sized is G itself when it can be checked now (and passes), else a goal that
%   checks it when it runs. Throws ga_refused(Why) for one too big. Fails for any other G.
sized(G, _, _) :-
    var(G), !,
    fail.
sized(G, _, Sized) :-
    arithmetic(G, Exprs), !,
    (   member(E, Exprs),
        grows(E)
    ->  forall(( member(E1, Exprs), ground(E1) ),   % written out: refused when loading
               catch(eval(E1, _), error(_, _), true)),
        Sized = ga_sizes:arithmetic(G)
    ;   G = (_ is E),
        term_variables(E, Vars),
        Vars \== []                         % a variable may hold an expression: checked
    ->  type_test(number, Vars, Test),      % inline when it holds a number
        Sized = ( Test -> G ; ga_sizes:arithmetic(G) )
    ).
sized(tab(N), _, Sized) :- !,
    repeat_goal(tab(N), N, Sized).
sized(tab(S, N), _, Sized) :- !,
    repeat_goal(tab(S, N), N, Sized).
sized(G, _, Sized) :-
    parsed_text(G, Text), !,
    (   ground(Text)
    ->  parse_length(Text),
        Sized = G
    ;   Sized = ga_sizes:parsing(Text, G)
    ).
sized(G, c(M, _, _), Sized) :-
    ( G = format(_, Args) ; G = format(_, _, Args) ), !,
    (   ground(Args)
    ->  small_integers(Args),
        Sized = G
    ;   Sized = ga_sizes:format_integers(Args, M:G)
    ).

%!  type_test(+Type, +Vars, -Test) is det.
%   Test: Type(V) of every variable V of Vars, in a conjunction written into a clause
%   (number and integer here for arithmetic, atomic in rules.pl's updates).
type_test(Type, [V], Test) :- !,
    Test =.. [Type, V].
type_test(Type, [V|Vs], (Test0, Test)) :-
    Test0 =.. [Type, V],
    type_test(Type, Vs, Test).

%   parsed_text(+G, -Text): G reads Text as a number or term (when Text is bound).
parsed_text(number_codes(_, Text), Text).
parsed_text(number_chars(_, Text), Text).
parsed_text(number_string(_, Text), Text).
parsed_text(atom_number(Text, _), Text).
parsed_text(name(_, Text), Text).
parsed_text(atom_to_term(Text, _, _), Text).
parsed_text(term_to_atom(_, Text), Text).
parsed_text(term_string(_, Text), Text).
parsed_text(term_string(_, Text, _), Text).
parsed_text(read_term_from_atom(Text, _, _), Text).

%!  parsing(?Text, :G) is nondet.
%   G, which reads Text (bound only now, if at all), after parse_length/1.
:- meta_predicate parsing(?, 0).

parsing(Text, G) :-
    (   var(Text) -> true ; parse_length(Text) ),
    call(G).

%   parse_length(+Text): no run of digits (or letters: 0x.. numbers) in Text longer than
%   max_digits/1 (only a text that long is scanned).
parse_length(Text) :-
    max_digits(Max),
    (   text_codes(Text, Length, Codes),
        Length > Max,
        longest_run(Codes, 0, 0, Run),
        Run > Max
    ->  format(string(Why), "a text with ~D digits in a row to read, more than ~D (SWI-Prolog reads a number's digits in time that grows with their square, without looking at the time limit: 300,000 took 9 s)", [Run, Max]),
        throw(ga_refused(Why))
    ;   true
    ).

text_codes(Text, Length, Codes) :-
    (   is_list(Text)
    ->  length(Text, Length),
        Length > 0,
        catch(atom_codes(Atom, Text), _, fail),
        atom_codes(Atom, Codes)
    ;   catch(atom_length(Text, Length), _, fail),
        atom_codes(Text, Codes)
    ).

longest_run([], Run, Longest0, Longest) :-
    Longest is max(Run, Longest0).
longest_run([C|Cs], Run, Longest0, Longest) :-
    (   code_type(C, alnum)
    ->  Run1 is Run + 1,
        longest_run(Cs, Run1, Longest0, Longest)
    ;   Longest1 is max(Run, Longest0),
        longest_run(Cs, 0, Longest1, Longest)
    ).

%   arithmetic(+G, -Exprs): G evaluates the expressions Exprs.
arithmetic(_ is E, [E]).
arithmetic(A < B, [A, B]).
arithmetic(A > B, [A, B]).
arithmetic(A =< B, [A, B]).
arithmetic(A >= B, [A, B]).
arithmetic(A =:= B, [A, B]).
arithmetic(A =\= B, [A, B]).

%   grows(@E): E may make a huge integer in one step: a power or shift written in it.
grows(E) :-
    sub_term(T, E),
    compound(T),
    compound_name_arity(T, Op, 2),
    memberchk(Op, [^, **, <<]),
    !.

%!  arithmetic(+G) is semidet.
%   Calls the arithmetic built-in G with its expressions evaluated step by step (eval/2).
arithmetic(X is E) :- !,
    eval(E, V),
    X is V.
arithmetic(G) :-
    G =.. [Op|Exprs],
    maplist(eval, Exprs, Values),
    G1 =.. [Op|Values],
    call(G1).

%   eval(+E, -V): V is E, each ^, ** and << of integers checked before it is computed.
eval(E, V) :-
    (   var(E)
    ->  V is E                              % is/2's instantiation error
    ;   number(E)
    ->  V = E
    ;   compound(E),
        \+ is_list(E)                       % ("a", [X]: a character code)
    ->  compound_name_arguments(E, Op, Args),
        maplist(eval, Args, Values),
        (   Values = [A, B], memberchk(Op, [^, **, <<])
        ->  power_bits(Op, A, B)
        ;   true
        ),
        compound_name_arguments(E1, Op, Values),
        V is E1
    ;   V is E
    ).

%   power_bits(+Op, +A, +B): the integer A Op B has at most max_integer_bits/1 bits.
power_bits(Op, A, B) :-
    (   integer(A), integer(B), B > 0,
        result_bits(Op, A, B, Bits),
        max_integer_bits(Max),
        Bits > Max
    ->  format(string(Why), "~w ~w ~w would make an integer of about ~D bits, more than ~D (SWI-Prolog computes and writes such integers without looking at the time limit)", [A, Op, B, Bits, Max]),
        throw(ga_refused(Why))
    ;   true
    ).

result_bits(<<, A, B, Bits) :- !,
    Bits is B + msb(max(abs(A), 1)).
result_bits(_, A, B, Bits) :-
    abs(A) > 1,
    Bits is B * (msb(abs(A)) + 1).

%   repeat_goal(+G, +N, -Sized): tab/1,2 of N spaces (an expression).
repeat_goal(G, N, Sized) :-
    (   ground(N)
    ->  catch(Count is N, _, fail),
        repeat_count(Count),
        Sized = G
    ;   Sized = ga_sizes:repeat(G)
    ),
    !.
repeat_goal(G, _, G).                       % (tab/1 raises its own error)

%!  repeat(+G) is det.
%   tab/1,2 (G) whose count is only known now.
repeat(G) :-
    ( G = tab(N) ; G = tab(_, N) ), !,
    Count is N,
    repeat_count(Count),
    call(G).

repeat_count(Count) :-
    max_repeat(Max),
    (   integer(Count), Count > Max
    ->  format(string(Why), "tab writes ~D spaces, more than ~D (an output bomb SWI-Prolog cannot interrupt)", [Count, Max]),
        throw(ga_refused(Why))
    ;   true
    ).

%!  format_integers(+Args, :G) is semidet.
%   format/2,3 (G) whose arguments Args are only known now: no integer among them too big
%   to write (see max_integer_bits/1).
:- meta_predicate format_integers(+, 0).

format_integers(Args, G) :-
    small_integers(Args),
    call(G).

small_integers(Args) :-
    max_integer_bits(Max),
    (   acyclic_term(Args),
        big_integer(Args, Max, T)
    ->  Bits is msb(abs(T)) + 1,
        format(string(Why), "an integer of ~D bits written, more than ~D (SWI-Prolog writes such integers without looking at the time limit)", [Bits, Max]),
        throw(ga_refused(Why))
    ;   true
    ).

%   big_integer(@T, +Max, -Big): Big is the first integer of at least Max bits in the
%   acyclic term T (lists walked in a loop: a long list needs no stack).
big_integer(T, Max, Big) :-
    (   integer(T)
    ->  T =\= 0,
        msb(abs(T)) >= Max,
        Big = T
    ;   compound(T)
    ->  (   T = [_|_]
        ->  big_integer_list(T, Max, Big)
        ;   compound_name_arity(T, _, Arity),
            big_integer_args(1, Arity, T, Max, Big)
        )
    ).

big_integer_list(List, Max, Big) :-
    (   nonvar(List),
        List = [Head|Tail]
    ->  (   big_integer(Head, Max, Big)
        ->  true
        ;   big_integer_list(Tail, Max, Big)
        )
    ;   big_integer(List, Max, Big)
    ).

big_integer_args(I, Arity, T, Max, Big) :-
    I =< Arity,
    arg(I, T, Arg),
    (   big_integer(Arg, Max, Big)
    ->  true
    ;   I1 is I + 1,
        big_integer_args(I1, Arity, T, Max, Big)
    ).

%!  printable(@T) is det.
%   The print/1 or log/1 action of T may write it: throws ga_error(Message) for a text
%   longer than max_print/1 characters, or an integer too big to write.
printable(T) :-
    max_print(Max),
    (   ( atom(T) ; string(T) )
    ->  atom_length(T, Length),
        (   Length > Max
        ->  too_long(Length, Max)
        ;   true
        )
    ;   catch(small_integers(T), ga_refused(Why), throw(ga_error(Why))),
        (   write_length(T, _, [quoted(true), max_length(Max)])
        ->  true
        ;   too_long(more, Max)
        )
    ).

too_long(Length, Max) :-
    (   integer(Length)
    ->  format(string(Message), "a text of ~D characters to write, more than ~D", [Length, Max])
    ;   format(string(Message), "a text of more than ~D characters to write", [Max])
    ),
    throw(ga_error(Message)).

%!  reportable(+T0, -T) is det.
%   T0 with every integer too big to convert for Python (more than max_integer_bits/1
%   bits) replaced by an atom saying its size: a warning about a rule whose bindings hold
%   one is still told (converting it would stop the agent, and take seconds).
reportable(T0, T) :-
    max_integer_bits(Max),
    (   acyclic_term(T0),
        big_integer(T0, Max, _)
    ->  replace_big(T0, Max, T)
    ;   T = T0
    ).

replace_big(T0, Max, T) :-
    (   integer(T0), T0 =\= 0, msb(abs(T0)) >= Max
    ->  Bits is msb(abs(T0)) + 1,
        format(atom(T), "<an integer of ~D bits>", [Bits])
    ;   compound(T0)
    ->  compound_name_arguments(T0, Name, Args0),
        maplist(replace_big_in(Max), Args0, Args),
        compound_name_arguments(T, Name, Args)
    ;   T = T0
    ).

replace_big_in(Max, T0, T) :-
    replace_big(T0, Max, T).

		 /*******************************
		 *      INLINE ARITHMETIC       *
		 *******************************/

%   An agent's conditions and knowledge are asserted with SWI-Prolog's optimise flag on
%   (with_optimise/1), so that the arithmetic of their clauses runs in the virtual
%   machine instead of calling is/2, >/2, ... (a call of such a built-in costs about 800
%   instructions, its inline form a tenth of that; the reference agent's cycle makes 30).
%   Inline, an arithmetic goal would raise its errors in the name of the clause instead of
%   the built-in's (`is/2: ...' would lose its prefix), and an unknown function would be
%   an error when the clause is asserted: so each arithmetic goal is first made one of two
%   forms (inline_clause/2):
%
%   - ( Test -> G ; ga_sizes:evaluated(G) ) when G runs inline, after Test, raising nothing
%     the built-in would word otherwise (inline_test/3): a comparison or is/2 of bare
%     variables and numbers after number(V) of each variable (numbers compare and unify
%     without error); an expression of integers, variables and the functions of
%     inline_function/1 after integer(V) of each (integer arithmetic cannot overflow; a
%     zero divisor names its function inline as the built-in does). Floats are left to
%     the built-in: their overflow would lose the `is/2' of its message inline;
%   - ga_sizes:evaluated(G), the built-in itself, for any other G.
%
%   A clause of these forms compiles to the same code whether or not it is read back
%   (clause/2) and asserted again, as agents launched from one program copy them.

%!  inline_clause(+Clause0, -Clause) is det.
%   Clause0 with each arithmetic goal of its body in one of the forms above.
inline_clause((Head :- Body0), (Head :- Body)) :- !,
    inline_arithmetic(Body0, Body).
inline_clause(Clause, Clause).

%!  inline_arithmetic(+Body0, -Body) is det.
%   Body0 with its arithmetic goals in the forms above, through the control constructs
%   SWI-Prolog compiles into the clause (a meta-call's goal is compiled when it runs, with
%   the flag off).
inline_arithmetic(G, G) :-
    var(G), !.
inline_arithmetic(( Test -> G ; ga_sizes:Slow ), Inline) :-
    guarded(Test, G, Slow, Exprs, Vars), !,     % made so already (by sized/3 or here)
    (   inline_test(Exprs, Vars, InlineTest)    % (other values: the slow path, as before)
    ->  Inline = ( InlineTest -> G ; ga_sizes:Slow )
    ;   Inline = ( Test -> ga_sizes:evaluated(G) ; ga_sizes:Slow )
    ).
inline_arithmetic((A, B), (IA, IB)) :- !,
    inline_arithmetic(A, IA),
    inline_arithmetic(B, IB).
inline_arithmetic((A ; B), (IA ; IB)) :- !,
    inline_arithmetic(A, IA),
    inline_arithmetic(B, IB).
inline_arithmetic((A | B), (IA | IB)) :- !,
    inline_arithmetic(A, IA),
    inline_arithmetic(B, IB).
inline_arithmetic((A -> B), (IA -> IB)) :- !,
    inline_arithmetic(A, IA),
    inline_arithmetic(B, IB).
inline_arithmetic((A *-> B), (IA *-> IB)) :- !,
    inline_arithmetic(A, IA),
    inline_arithmetic(B, IB).
inline_arithmetic(\+ A, \+ IA) :- !,
    inline_arithmetic(A, IA).
inline_arithmetic(M:G, M:IG) :- !,
    inline_arithmetic(G, IG).
inline_arithmetic(G, Inline) :-
    arithmetic(G, Exprs), !,
    term_variables(Exprs, Vars),
    (   inline_test(Exprs, Vars, Test)
    ->  Inline = ( Test -> G ; ga_sizes:evaluated(G) )
    ;   Inline = ga_sizes:evaluated(G)
    ).
inline_arithmetic(G, G).

%   guarded(+Test, +G, +Slow, -Exprs, -Vars): ( Test -> G ; ga_sizes:Slow ) is an
%   arithmetic goal G, whose expressions are Exprs with variables Vars, guarded by a test
%   of those variables, as sized/3 (number/1 of each) or inline_arithmetic/2
%   (inline_test/3) make it.
guarded(Test, G, Slow, Exprs, Vars) :-
    nonvar(G),
    arithmetic(G, Exprs),
    nonvar(Slow),
    ( Slow = arithmetic(G1) ; Slow = evaluated(G1) ),
    G1 == G,
    term_variables(Exprs, Vars),
    Vars \== [],
    (   type_test(number, Vars, Test0),
        Test0 == Test
    ->  true
    ;   inline_test(Exprs, Vars, Test0),
        Test0 == Test
    ).

%   inline_test(+Exprs, +Vars, -Test): the arithmetic goal whose expressions are Exprs,
%   with variables Vars (at least one), runs inline after Test raising nothing the
%   built-in would word otherwise (see the forms above); fails when it cannot.
inline_test(Exprs, Vars, Test) :-
    Vars \== [],
    (   maplist(bare, Exprs)
    ->  type_test(number, Vars, Test)
    ;   maplist(integral, Exprs)
    ->  type_test(integer, Vars, Test)
    ).

bare(E) :-
    (   var(E) -> true ; number(E) ).

%   integral(+E): E holds only variables, integers and the functions of inline_function/1.
integral(E) :-
    (   var(E)
    ->  true
    ;   integer(E)
    ->  true
    ;   compound(E),
        compound_name_arity(E, Name, Arity),
        inline_function(Name/Arity),
        E =.. [_|Args],
        maplist(integral, Args)
    ).

%   inline_function(?Function): evaluated inline on integers as by the built-in (no
%   division to a float, power or shift: those the built-in evaluates, the last two
%   checked step by step, see sized/3).
inline_function((+)/2).
inline_function((-)/2).
inline_function((*)/2).
inline_function((//)/2).
inline_function((mod)/2).
inline_function((rem)/2).
inline_function((div)/2).
inline_function((min)/2).
inline_function((max)/2).
inline_function((-)/1).
inline_function((+)/1).
inline_function((abs)/1).
inline_function((sign)/1).

%!  evaluated(+G) is semidet.
%   The arithmetic built-in G, called (this file is compiled without optimise).
evaluated(X is E) :- X is E.
evaluated(A < B) :- A < B.
evaluated(A > B) :- A > B.
evaluated(A =< B) :- A =< B.
evaluated(A >= B) :- A >= B.
evaluated(A =:= B) :- A =:= B.
evaluated(A =\= B) :- A =\= B.

%!  with_optimise(:Goal) is det.
%   Goal (asserting clauses made by inline_clause/2, or read back from ones that were, and
%   nothing that runs an agent's code) with the optimise flag on, set once for all of them.
%   (Called as ga_sizes:with_optimise/1, Goal is in ga_sizes unless it names its module.)
:- meta_predicate with_optimise(0).

with_optimise(Goal) :-
    current_prolog_flag(optimise, Optimise),
    setup_call_cleanup(set_prolog_flag(optimise, true),
                       once(Goal),
                       set_prolog_flag(optimise, Optimise)).
