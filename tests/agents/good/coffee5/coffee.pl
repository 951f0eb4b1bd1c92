% Knowledge shared by the GOAL 5 style coffee machines (each agent #imports this file).
:- dynamic have/1, offers/2.

% What a product is made from.
needs(coffee, water).
needs(coffee, grounds).
needs(grounds, beans).

% Told facts (not questions or requests) can be forgotten once believed.
plain(Message) :- Message \= int(_), Message \= imp(_).
