% What each product needs (knowledge of both machines).
requires(coffee, water).
requires(coffee, grounds).
requires(grounds, beans).
