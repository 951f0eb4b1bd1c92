/*  What confine.pl knows about SWI-Prolog's built-ins (included into ga_confine): which it
    refuses, sandbox or not, and how an agent's catch/3 and cleanup handlers are made to
    let the runtime's limits through.
*/

%   Built-ins no agent may call, sandbox or not: the other agents run in the same process.
process_wide(set_prolog_flag/2).
process_wide(create_prolog_flag/3).
process_wide(consult/1).
process_wide(load_files/1).
process_wide(load_files/2).             % its stream(S) option loads any text under any name
process_wide('[|]'/2).                  % [File, ...]: consult
process_wide(reexport/1).
process_wide(reexport/2).
process_wide(autoload/1).
process_wide(autoload/2).
process_wide(ensure_loaded/1).
process_wide(include/1).
process_wide(make/0).
process_wide(qcompile/1).
process_wide(qcompile/2).
process_wide(load_foreign_library/1).
process_wide(load_foreign_library/2).
process_wide(use_foreign_library/1).
process_wide(use_foreign_library/2).
process_wide(open_shared_object/2).
process_wide(open_shared_object/3).
process_wide(chdir/1).
process_wide(halt/0).
process_wide(halt/1).
process_wide(abort/0).
process_wide(thread_signal/2).
process_wide(set_prolog_stack/2).
process_wide(garbage_collect_atoms/0).
process_wide(thread_create/2).          % a thread runs outside the agent's limits, beside
process_wide(thread_create/3).          % the one thread the runtime drives Prolog from
process_wide(thread_create_in_pool/4).
process_wide(concurrent/3).
process_wide(concurrent_forall/2).
process_wide(concurrent_forall/3).
process_wide(concurrent_maplist/2).
process_wide(concurrent_maplist/3).
process_wide(concurrent_maplist/4).
process_wide(first_solution/3).
process_wide(call_in_thread/2).
process_wide(on_signal/3).              % the process's signal handlers (Ctrl-C, the watchdog's)
process_wide(format_predicate/2).       % a format directive for every format/2,3 call
process_wide(prolog_listen/2).          % called on events of every agent (their clauses)
process_wide(prolog_listen/3).
process_wide(prolog_unlisten/2).
process_wide(at_halt/1).                % runs when the process ends, outside every limit
process_wide(cancel_halt/1).
process_wide(alarm/3).                  % library(time): a goal run later, in whatever query
process_wide(alarm/4).                  % (another agent's) is running then
process_wide(alarm_at/3).
process_wide(alarm_at/4).
process_wide(remove_alarm/1).
process_wide(install_alarm/1).
process_wide(install_alarm/2).
process_wide(uninstall_alarm/1).
process_wide(set_prolog_IO/3).
process_wide(expects_dialect/1).       % the process's dialect flag and global operators
%   Issue 24 (the review of SWI-Prolog's manual, docs/confinement-review.md, gives each its
%   section): what is shared by every agent and the runtime, or holds up the whole process.
process_wide(working_directory/2).     % where relative --save-beliefs, --trace-file land
process_wide(unload_file/1).           % the runtime's own Prolog files
process_wide(require/1).               % loads any library (the sandbox's list included)
process_wide(initialize/0).            % runs the initialization goals of loaded files
process_wide((initialization)/2).      % as a goal (a directive is prepare_directive/3's)
process_wide(compile_aux_clauses/1).   % into the module being loaded, else user
process_wide(version/1).               % the process's banner
process_wide(edit/0).                  % an editor, waited for
process_wide(edit/1).
process_wide(prolog_alert_signal/2).   % the signal the watchdog's thread_signal/2 uses
process_wide(sig_atomic/1).            % its goal runs with signals held back: no limit,
process_wide(sig_block/1).             % no SIGTERM stops it; blocking or dropping the
process_wide(sig_unblock/1).           % runtime's signals has the same effect
process_wide(sig_pending/1).
process_wide(sig_remove/2).
process_wide(set_input/1).             % the current input and output of the one thread
process_wide(set_output/1).            % that runs every agent (Edinburgh I/O included)
process_wide(see/1).
process_wide(seen/0).
process_wide(tell/1).
process_wide(append/1).
process_wide(told/0).
process_wide(set_stream/2).            % aliases (user_output, ...) and the standard streams
process_wide(set_system_IO/3).
process_wide(register_iri_scheme/3).   % a hook for every open/3 of the process
process_wide(with_tty_raw/1).          % the terminal's mode
process_wide(get_single_char/1).
process_wide(prompt/2).
process_wide(set_locale/1).            % how every agent's format/2 writes numbers
process_wide(locale_destroy/1).
process_wide(setlocale/3).             % the C library's: how the process writes floats
process_wide(char_conversion/2).       % the reader's table
process_wide(set_random/1).            % the random numbers of every agent
process_wide(setenv/2).                % the process's environment
process_wide(unsetenv/1).
process_wide(break/0).                 % an interactive top level on the terminal
process_wide(prolog/0).
process_wide(protocol/1).              % a copy of every agent's terminal I/O
process_wide(protocola/1).
process_wide(noprotocol/0).
process_wide(trace/0).                 % the debugger: it prompts on the terminal, and its
process_wide(trace/1).                 % mode is the thread's, every agent's
process_wide(trace/2).
process_wide(notrace/0).
process_wide(debug/0).
process_wide(nodebug/0).
process_wide(spy/1).
process_wide(nospy/1).
process_wide(nospyall/0).
process_wide(leash/1).
process_wide(visible/1).
process_wide(style_check/1).
process_wide(prolog_skip_level/2).
process_wide(prolog_skip_frame/1).
process_wide(prolog_interrupt/0).
process_wide(prolog_debug/1).
process_wide(prolog_nodebug/1).
process_wide(profile/1).               % the profiler is the process's
process_wide(profile/2).
process_wide(profiler/2).
process_wide(reset_profiler/0).
process_wide(set_prolog_gc_thread/1).
process_wide(set_malloc/1).
process_wide(abolish_all_tables/0).    % every agent's tables
process_wide(abolish_private_tables/0).
process_wide(abolish_shared_tables/0).
process_wide(abolish_nonincremental_tables/0).
process_wide(abolish_nonincremental_tables/1).
process_wide(abolish_monotonic_tables/0).
process_wide(thread_exit/1).           % the thread that runs every agent
process_wide(thread_join/1).
process_wide(thread_join/2).
process_wide(thread_detach/1).
process_wide(thread_alias/1).
process_wide(thread_at_exit/1).        % run when the process ends, outside every limit
process_wide((thread_initialization)/1).
process_wide(thread_setconcurrency/2).
process_wide(thread_affinity/3).
process_wide(thread_wait/2).           % waits for other threads: there are none
process_wide(thread_update/2).
process_wide(thread_send_message/2).   % the thread's message queue and named queues are
process_wide(thread_send_message/3).   % shared by every agent: a channel between them
process_wide(thread_get_message/1).
process_wide(thread_get_message/2).
process_wide(thread_get_message/3).
process_wide(thread_peek_message/1).
process_wide(thread_peek_message/2).
process_wide(message_queue_create/1).
process_wide(message_queue_create/2).
process_wide(message_queue_destroy/1).
process_wide(message_queue_property/2).
process_wide(message_queue_set/2).
process_wide(mutex_create/1).          % named mutexes are the process's: with one thread
process_wide(mutex_create/2).          % they only serve as a channel between agents
process_wide(mutex_destroy/1).
process_wide(mutex_lock/1).
process_wide(mutex_trylock/1).
process_wide(mutex_unlock/1).
process_wide(mutex_unlock_all/0).
process_wide(mutex_property/2).
process_wide(with_mutex/2).
process_wide(call_with_time_limit/2).  % library(time): an alarm thread, as alarm/4
process_wide(interactor/0).            % library(threadutil): threads and consoles
process_wide(attach_console/0).
process_wide(tdebug/0).
process_wide(tdebug/1).
process_wide(tnodebug/0).
process_wide(tnodebug/1).
process_wide(tspy/1).
process_wide(tspy/2).
process_wide(tprofile/1).
process_wide(prolog_server/2).         % library(prolog_server): a top level on a socket
process_wide(engine_create/3).         % an engine runs its goal outside the agent's
process_wide(engine_create/4).         % limits (their own stacks; not confined after a
process_wide(engine_post/2).           % yield)
process_wide(engine_post/3).
process_wide(engine_next/2).
process_wide(engine_next_reified/2).
process_wide(engine_destroy/1).
process_wide(engine_yield/1).
process_wide(engine_fetch/1).
process_wide(current_engine/1).
process_wide(close_shared_object/1).   % foreign code
process_wide(call_shared_object_function/2).
process_wide(qsave_program/1).         % a saved state holds every agent's mind
process_wide(qsave_program/2).
process_wide(autoload_all/0).
process_wide(autoload_path/1).
process_wide(make_library_index/1).
process_wide(make_library_index/2).
process_wide(reload_library_index/0).
process_wide(attach_packs/0).
process_wide(attach_packs/1).
process_wide(attach_packs/2).
process_wide(license/1).
process_wide(license/2).

%   Attribute hooks run in the module an attribute is named after: put_attr(X, freeze, G)
%   would call any G, unchecked, when X is bound.
attribute_hook(put_attr/3).
attribute_hook(put_attrs/2).

%   Built-ins that enumerate modules or atoms, or reach into frames or the module system.
private(current_module/1).
private(module_property/2).
private(current_atom/1).
private(current_blob/2).
private(current_functor/2).
private(current_key/1).
private(current_flag/1).
private(prolog_current_frame/1).
private(prolog_frame_attribute/3).
private(prolog_choice_attribute/3).
private(prolog_current_choice/1).       % a choice point of the runtime's, to cut to
private(prolog_cut_to/1).
private((@)/2).
private(set_module/1).
private(module/2).
private(add_import_module/3).
private(delete_import_module/2).
private(context_module/1).
private(strip_module/3).
private(module/1).                      % the top level's module
private(import_module/2).               % with an unbound module: every module
private(default_module/2).
private(abolish_module_tables/1).       % names a module

%   Built-ins that print a message or term: a message format(F, Args) or a line F-Args
%   runs a goal for ~@ in F, and the write option portray_goal(G) calls G.
printing_goal(G) :-
    functor(G, Name, Arity),
    memberchk(Name/Arity, [print_message/2, print_message_lines/3, message_to_codes/3,
                           debug/3, write_term/2, write_term/3, print/2, write_length/3,
                           portray_clause/3, assertion_failed/2]).

sandbox_library(Name) :-
    memberchk(Name, [lists, apply, aggregate, pairs, assoc, ordsets, ugraphs, rbtrees, nb_set,
                     heaps, random, solution_sequences, yall, occurs, terms, sort, option,
                     error, gensym, varnumbers, when, dif, dicts, strings, tables,
                     'dcg/basics', 'dcg/high_order']).

%   Under the sandbox, library(sandbox) must find the call safe (its goal arguments,
%   checked here, replaced by a safe placeholder of the same arity). The library is loaded
%   when the first sandboxed agent is (load_sandbox/0): it loads library(apply_macros),
%   whose goal expansion then applies to every file compiled in the process (a run without
%   --sandbox must not change how Prolog compiles the user's own files).
sandbox_allows(_, c(_, false, _)) :- !.
sandbox_allows(G, _) :-
    own_introspection(G), !.
sandbox_allows(G, c(M, true, _)) :-
    placeholders(G, Probe),
    catch(sandbox:safe_goal(M:Probe), E, unsafe(E, G)).

%!  load_sandbox is det.
%   Loads library(sandbox) before the first sandboxed agent is read (load/5), not under an
%   agent's inference limit in the middle of a rule.
load_sandbox :-
    use_module(library(sandbox), []).

%   stoppable(+Goal0, +Ctx, -Goal): agent code never holds back what stops it. Its
%   catch/3 lets the runtime's exceptions pass (a limit, an abort: a catch-all whose
%   recovery runs the runaway goal again would run for ever), and its cleanup handlers run
%   as ordinary code (see cleanup_call/4).
stoppable(catch(G, C, R), c(M, _, _), catch(G, E, ga_confine:recover(E, C, M:R))) :- !.
stoppable(catch_with_backtrace(G, C, R), c(M, _, _),
          catch_with_backtrace(G, E, ga_confine:recover(E, C, M:R))) :- !.
stoppable(setup_call_cleanup(S, G, C), c(M, _, _),
          ga_confine:cleanup_call(M:S, M:G, _, M:C)) :- !.
stoppable(setup_call_catcher_cleanup(S, G, K, C), c(M, _, _),
          ga_confine:cleanup_call(M:S, M:G, K, M:C)) :- !.
stoppable(call_cleanup(G, C), c(M, _, _), ga_confine:cleanup_call(true, M:G, _, M:C)) :- !.
stoppable(call_cleanup(G, K, C), c(M, _, _), ga_confine:cleanup_call(true, M:G, K, M:C)) :- !.
stoppable(G, _, G).

%!  recover(+Ball, ?Catcher, :Recovery) is nondet.
%   The recovery of an agent's catch/3: the runtime's exceptions pass on.
recover(Ball, Catcher, Recovery) :-
    (   runtime_ball(Ball)
    ->  throw(Ball)
    ;   Ball = Catcher
    ->  call(Recovery)
    ;   throw(Ball)
    ).

%!  agent_throw(+Ball) is det.
%   An agent's throw/1 of a ball only known at run time (see prepare/3).
agent_throw(Ball) :-
    (   runtime_ball(Ball)
    ->  refuse_ball(Ball)
    ;   throw(Ball)
    ).

refuse_ball(Ball) :-
    refuse("throw(~q): this exception is the runtime's (a limit, an abort), not an agent's",
           [Ball]).

runtime_ball(Ball) :-
    nonvar(Ball),
    (   Ball == '$aborted'
    ;   Ball = ga_limit(_)
    ;   Ball == '$ga_python'
    ;   Ball == inference_limit_exceeded
    ;   Ball = unwind(_)
    ),
    !.

%!  cleanup_call(:Setup, :Goal, ?Catcher, :Cleanup) is semidet.
%   An agent's setup_call_cleanup/3 (and setup_call_catcher_cleanup/4, call_cleanup/2):
%   Goal's first solution only, and Cleanup run as ordinary code after it. SWI-Prolog runs
%   cleanup handlers with signals held back, so neither the time limit nor an abort (nor
%   SIGTERM) could stop a runaway one; a limit or an abort that ends Goal skips Cleanup.
cleanup_call(Setup, Goal, Catcher, Cleanup) :-
    once(Setup),
    (   catch(Goal, Ball, true)
    ->  (   var(Ball) -> Outcome = exit ; Outcome = exception(Ball) )
    ;   Outcome = fail
    ),
    (   Outcome = exception(Stop), runtime_ball(Stop)
    ->  throw(Stop)
    ;   Catcher = Outcome
    ->  ignore(Cleanup)
    ;   true
    ),
    (   Outcome = exception(Error)
    ->  throw(Error)
    ;   Outcome == exit
    ).
