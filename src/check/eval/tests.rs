//! The evaluator's tests: operators, lists, functions, built-ins, budgets.

use crate::check::{check_str, Shape, SymbolKind};
use crate::diag::{codes, Diagnostic};
use std::path::Path;

/// The value of `expr` used as a sphere's radius.
fn radius(expr: &str) -> f64 {
    let src = format!(
        "camera {{ position <0, 0, 5> look_at <0, 0, 0> }}\n\
         sphere {{ center <0, 0, 0> radius {expr} }}\n"
    );
    let c = check_str(Path::new("t.pts"), &src);
    let scene = c
        .scene
        .unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    match scene.objects[0].shape {
        Shape::Sphere { radius, .. } => radius,
        ref s => panic!("not a sphere: {s:?}"),
    }
}

/// The value of `expr` after the statements `before`, or the first
/// diagnostic's code.
fn value(before: &str, expr: &str) -> Result<super::Value, String> {
    evaluate(super::MAX_WORK, before, expr).map_err(|d| d.code.to_string())
}

/// The value of `expr` after the statements `before`, evaluated with a
/// budget of `work` steps, or the first diagnostic.
fn evaluate(work: u64, before: &str, expr: &str) -> Result<super::Value, Diagnostic> {
    use crate::syntax::ast::Statement;
    let src = format!("{before}\nlet v__ = {expr};");
    let file = crate::syntax::parse(crate::source::FileId(0), &src, &crate::check::kinds::NAMES)?;
    let mut env = super::Env::with_work(work);
    let mut diags = crate::diag::Diagnostics::new();
    let mut out = None;
    for st in &file.statements {
        match st {
            Statement::Let {
                name, value, span, ..
            } => {
                let v = super::eval(value, &mut env, &mut diags);
                if name.name == "v__" {
                    out = v.clone();
                }
                let named = (name.name.as_str(), name.span);
                env.define(SymbolKind::Constant, named, *span, v);
            }
            Statement::Function {
                name,
                params,
                body,
                span,
            } => {
                let params = (params.iter())
                    .map(|p| {
                        let kind = SymbolKind::Parameter;
                        let def = env.symbols.define(kind, &p.name, p.span, *span);
                        (p.name.clone(), def)
                    })
                    .collect();
                let f = super::Function {
                    name: name.name.clone(),
                    params,
                    body: body.clone(),
                };
                let value = Some(super::Value::Function(std::sync::Arc::new(f)));
                let named = (name.name.as_str(), name.span);
                env.define(SymbolKind::Function, named, *span, value);
            }
            _ => {}
        }
    }
    match diags.items.first() {
        Some(d) => Err(d.clone()),
        None => Ok(out.expect("a value")),
    }
}

fn num(before: &str, expr: &str) -> f64 {
    match value(before, expr) {
        Ok(super::Value::Num(x)) => x,
        other => panic!("{expr}: {other:?}"),
    }
}

fn boolean(expr: &str) -> bool {
    match value("", expr) {
        Ok(super::Value::Bool(b)) => b,
        other => panic!("{expr}: {other:?}"),
    }
}

#[test]
fn comparisons_and_logic_bind_below_arithmetic() {
    for (expr, want) in [
        ("1 + 1 == 2", true),
        ("2 * 3 < 5", false),
        ("1 < 2 && 2 < 3", true),
        ("1 > 2 || 2 < 3 && 3 < 4", true),
        ("(1 > 2 || 2 < 3) && 3 > 4", false),
        ("!(1 < 2)", false),
        ("!!true", true),
        ("1 <= 1 && 1 >= 1 && 1 != 2", true),
        ("<1, 2, 3> == <1, 2, 3>", true),
        ("[1, \"a\"] != [1, \"a\"]", false),
        ("\"ab\" == \"a\" + \"b\"", true),
        ("rgb 1 == rgb <1, 1, 1>", true),
    ] {
        assert_eq!(boolean(expr), want, "{expr}");
    }
    // `&&` and `||` stop at the first operand that decides: the right
    // side would fail (index out of range, division by zero).
    assert!(!boolean("[1][0] > 1 && [1][5] > 0"));
    assert!(boolean("true || 1 / 0 > 0"));
    assert_eq!(value("", "1 < true").unwrap_err(), codes::TYPE_MISMATCH);
    assert_eq!(value("", "1 && true").unwrap_err(), codes::TYPE_MISMATCH);
}

#[test]
fn lists_index_and_measure() {
    let before = "let xs = [10, <1, 2, 3>, \"abc\", [4, 5]];";
    assert_eq!(num(before, "xs[0]"), 10.0);
    assert_eq!(num(before, "xs[1][2]"), 3.0);
    assert_eq!(num(before, "xs[3][1]"), 5.0);
    assert_eq!(num(before, "len(xs) + len(xs[2]) + len([])"), 7.0);
    assert_eq!(num(before, "len(xs + [1, 2])"), 6.0);
    assert_eq!(value(before, "xs[2][1]"), Ok(super::Value::Str("b".into())));
    assert_eq!(
        value(before, "xs[4]").unwrap_err(),
        codes::INDEX_OUT_OF_RANGE
    );
    assert_eq!(
        value(before, "xs[-1]").unwrap_err(),
        codes::INDEX_OUT_OF_RANGE
    );
    assert_eq!(value(before, "xs[0.5]").unwrap_err(), codes::TYPE_MISMATCH);
    assert_eq!(value(before, "xs[0][0]").unwrap_err(), codes::TYPE_MISMATCH);
}

#[test]
fn conditionals_evaluate_only_the_chosen_arm() {
    assert_eq!(
        num(
            "let a = 2;",
            "if a < 1 { 10 } else if a < 3 { 20 } else { 30 }"
        ),
        20.0
    );
    assert_eq!(
        num(
            "let a = 5;",
            "if a < 1 { 10 } else if a < 3 { 20 } else { 30 }"
        ),
        30.0
    );
    // The arm not taken would divide by zero.
    assert_eq!(num("", "if true { 1 } else { 1 / 0 }"), 1.0);
    assert_eq!(
        value("", "if 1 { 1 } else { 2 }").unwrap_err(),
        codes::TYPE_MISMATCH
    );
}

#[test]
fn functions_see_their_parameters_and_the_file_and_recurse_within_bounds() {
    let before =
        "let k = 3;\nfn scale(x) = x * k;\nfn fact(n) = if n <= 1 { 1 } else { n * fact(n - 1) };";
    assert_eq!(num(before, "scale(2)"), 6.0);
    assert_eq!(num(before, "fact(10)"), 3_628_800.0);
    assert_eq!(
        value(before, "fact(100)").unwrap_err(),
        codes::RECURSION_LIMIT
    );
    assert_eq!(
        value(before, "scale(1, 2)").unwrap_err(),
        codes::WRONG_ARGUMENT_COUNT
    );
    assert_eq!(value(before, "k(1)").unwrap_err(), codes::TYPE_MISMATCH);
    assert_eq!(
        value(before, "scal(1)").unwrap_err(),
        codes::UNKNOWN_FUNCTION
    );
    // A constant named like a built-in leaves the built-in callable.
    assert_eq!(num("let max = 1;", "max(max, 2)"), 2.0);
    // A function's body does not see its caller's names.
    assert_eq!(
        value("fn f(x) = x + y;\nfn g(y) = f(1);", "g(2)").unwrap_err(),
        codes::UNKNOWN_NAME
    );
}

#[test]
fn strings_and_numbers_format() {
    let s = |expr: &str| match value("", expr) {
        Ok(super::Value::Str(s)) => s.to_string(),
        other => panic!("{expr}: {other:?}"),
    };
    assert_eq!(s("\"frame_\" + str(7, 4) + \".png\""), "frame_0007.png");
    assert_eq!(s("str(-3, 3)"), "-003");
    assert_eq!(s("str(0.25)"), "0.25");
    assert_eq!(s("str(<1, 2.5, 3>)"), "<1, 2.5, 3>");
    assert_eq!(s("str([1, \"a\"])"), "[1, a]");
    assert_eq!(value("", "str(1, 40)").unwrap_err(), codes::DOMAIN);
    assert_eq!(value("", "\"a\" + 1").unwrap_err(), codes::TYPE_MISMATCH);
}

#[test]
fn random_numbers_are_a_pure_function_of_seed_and_index() {
    let a: Vec<f64> = (0..1000).map(|i| super::random(7.0, i as f64)).collect();
    let b: Vec<f64> = (0..1000).map(|i| super::random(7.0, i as f64)).collect();
    assert_eq!(a, b);
    assert!(a.iter().all(|x| (0.0..1.0).contains(x)));
    // Another seed, another sequence; uniform enough to fill ten bins.
    assert_ne!(super::random(8.0, 0.0), a[0]);
    assert_eq!(super::random(-0.0, 3.0), super::random(0.0, 3.0));
    let mut bins = [0; 10];
    for x in &a {
        bins[(x * 10.0) as usize] += 1;
    }
    assert!(bins.iter().all(|&n| (70..130).contains(&n)), "{bins:?}");
    let mean = a.iter().sum::<f64>() / a.len() as f64;
    assert!((mean - 0.5).abs() < 0.03, "{mean}");
}

#[test]
fn new_built_in_functions() {
    assert_eq!(num("", "floor(-1.5) + ceil(1.2) + round(2.5)"), 3.0);
    assert_eq!(num("", "clamp(5, 0, 1) + clamp(-1, 0, 1)"), 1.0);
    assert!((num("", "atan2(1, 1)") - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    assert!((num("", "exp(log(3))") - 3.0).abs() < 1e-12);
    assert!((num("", "asin(1) + acos(1)") - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert_eq!(value("", "asin(2)").unwrap_err(), codes::DOMAIN);
    assert_eq!(value("", "log(0)").unwrap_err(), codes::DOMAIN);
    assert_eq!(value("", "clamp(0, 1, -1)").unwrap_err(), codes::DOMAIN);
}

#[test]
fn operators_bind_and_associate_as_in_arithmetic() {
    // Each wrong precedence or associativity gives another (or a
    // negative, rejected) value.
    for (expr, want) in [
        ("10 - 2 * 3 - 1", 3.0),
        ("2 * 3 + 4 * 5", 26.0),
        ("1 - 2 + 3", 2.0),
        ("12 / 3 * 2", 8.0),
        ("8 / 2 / 2", 2.0),
        ("2 - -3", 5.0),
        ("-2 * -3", 6.0),
        ("- - 3", 3.0),
        ("-(1 - 3) * 2", 4.0),
        ("2 * (1 + 2) - 1", 5.0),
        ("1 + 2 * 3 * 2 - 4 / 2", 11.0),
        // `%` binds as `*` and `/`, with the sign of the dividend.
        ("7 % 4", 3.0),
        ("1 + 7 % 4 * 2", 7.0),
        ("7.5 % 2", 1.5),
        ("10 - -7 % 4", 13.0),
    ] {
        assert_eq!(radius(expr), want, "{expr}");
    }
}

/// The components of the vector `expr`.
fn vector(expr: &str) -> Vec<f64> {
    match value("", expr) {
        Ok(super::Value::Vector(v)) => v.to_vec(),
        other => panic!("{expr}: {other:?}"),
    }
}

/// The message of the error `expr` gives.
fn message(expr: &str) -> String {
    evaluate(super::MAX_WORK, "", expr).unwrap_err().message
}

#[test]
fn vectors_are_scaled_before_they_are_squared() {
    // Issue 35, item 12: the squared length overflowed (a zero vector) or
    // underflowed ("cannot normalize a zero vector").
    assert_eq!(vector("normalize(<1e200, 0, 0>)"), [1.0, 0.0, 0.0]);
    assert_eq!(vector("normalize(<1e-200, 0, 0>)"), [1.0, 0.0, 0.0]);
    assert_eq!(vector("normalize(<0, -5e-324, 0>)"), [0.0, -1.0, 0.0]);
    let u = vector("normalize(<1e300, 1e300, 0>)");
    assert!(
        (u[0] - 0.5f64.sqrt()).abs() < 1e-15 && u[0] == u[1],
        "{u:?}"
    );
    assert_eq!(num("", "length(<1e200, 0, 0>)"), 1e200);
    assert_eq!(num("", "length(<0, 0, -1e-300>)"), 1e-300);
    let l = num("", "length(<3e-200, 4e-200, 0>)");
    assert!((l / 5e-200 - 1.0).abs() < 1e-15, "{l}");
    assert_eq!(num("", "dot(<1e200, 1e200, 0>, <1e200, -1e200, 0>)"), 0.0);
    assert_eq!(num("", "dot(<1e200, 0, 0>, <1e-200, 0, 0>)"), 1.0);
    assert_eq!(
        vector("cross(<1e200, 0, 0>, <0, 1e-200, 0>)"),
        [0.0, 0.0, 1.0]
    );
    assert_eq!(vector("cross(<1e300, 0, 0>, <1e300, 0, 0>)"), [0.0; 3]);
    // Too large is too large, and says so.
    for expr in [
        "length(<1.7e308, 1.7e308, 0>)",
        "dot(<1e200, 0, 0>, <1e200, 0, 0>)",
        "cross(<1e200, 0, 0>, <0, 1e200, 0>)",
    ] {
        assert_eq!(value("", expr).unwrap_err(), codes::NOT_FINITE, "{expr}");
        assert!(
            message(expr).contains("1.8e308"),
            "{expr}: {}",
            message(expr)
        );
    }
    assert_eq!(
        value("", "normalize(<0, 0, 0>)").unwrap_err(),
        codes::DOMAIN
    );
}

#[test]
fn powers_logs_and_indexes_at_the_edges_say_what_is_wrong() {
    assert_eq!(num("", "pow(-2, 3)"), -8.0);
    assert_eq!(num("", "pow(1e-300, 2)"), 0.0);
    assert_eq!(num("", "exp(-1000)"), 0.0);
    assert_eq!(num("", "log(5e-324)"), (5e-324f64).ln());
    assert_eq!(value("", "pow(-8, 1 / 3)").unwrap_err(), codes::DOMAIN);
    assert!(message("pow(-8, 0.5)").contains("negative number to a fractional power"));
    assert_eq!(value("", "pow(0, -1)").unwrap_err(), codes::DOMAIN);
    for expr in ["pow(10, 400)", "exp(1000)", "1 / 1e-320", "degrees(1e307)"] {
        assert_eq!(value("", expr).unwrap_err(), codes::NOT_FINITE, "{expr}");
        assert!(
            message(expr).contains("too large"),
            "{expr}: {}",
            message(expr)
        );
    }
    assert_eq!(num("", "floor(1e300) / 1e300"), 1.0);
    // Indexes: huge ones are out of range (said in a readable form),
    // fractions are not indexes.
    assert_eq!(
        message("[1, 2][1e300]"),
        "index 1e300 is out of range for a list of 2"
    );
    assert_eq!(
        value("", "\"ab\"[-1e300]").unwrap_err(),
        codes::INDEX_OUT_OF_RANGE
    );
    assert_eq!(
        message("[1, 2][0.5]"),
        "an index must be a whole number, found 0.5"
    );
    assert_eq!(value("", "str(1, 1e300)").unwrap_err(), codes::DOMAIN);
}

/// Statements that make `a` and `b`: two lists of 10,000 equal items,
/// neither a copy of the other.
const TWO_LISTS: &str = "let t = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10];\n\
    let h = t + t + t + t + t + t + t + t + t + t;\n\
    let k = h + h + h + h + h + h + h + h + h + h;\n\
    let a = k + k + k + k + k + k + k + k + k + k;\n\
    let b = k + k + k + k + k + k + k + k + k + k;";

#[test]
fn comparing_and_printing_cost_their_work() {
    // Issue 35, item 9: `==` of two lists visits their items, each a step.
    let code = |r: Result<super::Value, Diagnostic>| r.map_err(|d| d.code);
    assert_eq!(
        code(evaluate(20_000, TWO_LISTS, "a == b")),
        Ok(super::Value::Bool(true))
    );
    let d = evaluate(5_000, TWO_LISTS, "a == b").unwrap_err();
    assert_eq!(d.code, codes::EVALUATION_TOO_LONG);
    assert_eq!(
        d.message,
        "the expressions of this scene take more than 5,000 steps of work in all"
    );
    // A list is equal to itself without a look; lists of other lengths
    // differ at once.
    assert_eq!(
        code(evaluate(10, TWO_LISTS, "a == a")),
        Ok(super::Value::Bool(true))
    );
    assert_eq!(
        code(evaluate(10, TWO_LISTS, "a == k")),
        Ok(super::Value::Bool(false))
    );
    // `str` writes at most a string's worth, a step a byte.
    assert_eq!(
        code(evaluate(1_000, TWO_LISTS, "str(a)")),
        Err(codes::VALUE_TOO_LARGE)
    );
    assert_eq!(
        code(evaluate(100, TWO_LISTS, "str(t)")),
        Ok(super::Value::Str("[1, 2, 3, 4, 5, 6, 7, 8, 9, 10]".into()))
    );
    assert_eq!(
        code(evaluate(20, TWO_LISTS, "str(t)")),
        Err(codes::EVALUATION_TOO_LONG)
    );
    // Long vectors cost by their components, whether added or negated.
    let long = format!("let v = <{}>;", vec!["1"; 1000].join(", "));
    assert!(evaluate(1_000, &long, "len(v + v)").is_ok());
    assert_eq!(
        code(evaluate(400, &long, "v + v")),
        Err(codes::EVALUATION_TOO_LONG)
    );
    assert_eq!(
        code(evaluate(400, &long, "-v")),
        Err(codes::EVALUATION_TOO_LONG)
    );
}

#[test]
fn a_function_costs_the_expressions_it_evaluates() {
    // Issue 35, item 9: a long function called often ran for minutes.
    let terms: Vec<String> = (0..100).map(|k| format!("x * {k}")).collect();
    let f = format!("fn f(x) = {};", terms.join(" + "));
    // 100 products of two names (three steps each), their sum, the call.
    assert!(evaluate(400, &f, "f(1)").is_ok());
    assert_eq!(
        evaluate(200, &f, "f(1)").unwrap_err().code,
        codes::EVALUATION_TOO_LONG
    );
    // At the top level, an expression's own text bounds it: free.
    let sum = vec!["1"; 1000].join(" + ");
    assert!(evaluate(10, "", &sum).is_ok());
}

#[test]
fn lists_nest_at_most_so_deep() {
    // A chain of `let`s nested a list 300,000 deep: dropping it overflowed
    // the stack.
    let mut before = String::from("let l0 = [];\n");
    for k in 1..super::MAX_LIST_DEPTH {
        before += &format!("let l{k} = [l{}];\n", k - 1);
    }
    // `l255` nests 256 deep, the most.
    let (deepest, next) = (super::MAX_LIST_DEPTH - 1, super::MAX_LIST_DEPTH - 2);
    assert!(value(&before, &format!("[l{next}] == [l{next}]")).is_ok());
    assert_eq!(
        value(&before, &format!("[l{deepest}]")).unwrap_err(),
        codes::VALUE_TOO_LARGE
    );
}

#[test]
fn suggestions_stop_when_their_budget_is_spent() {
    let mut env = super::Env::new();
    let names = ["radius", "center"];
    assert_eq!(env.suggest("radus", 2, names), Some("radius"));
    env.suggestions = super::budget::Work::new(1);
    assert_eq!(env.suggest("radus", 2, names), None);
}

#[test]
fn povray_forms_that_ptsc_accepts_evaluate_as_in_povray() {
    // `pi`, `x`/`y`/`z`, `clock_delta` are predefined; `int` truncates
    // towards zero, `mod` keeps the sign of its first argument (POV-Ray's).
    assert!((radius("pi") - std::f64::consts::PI).abs() < 1e-15);
    assert_eq!(radius("int(2.7)"), 2.0);
    assert_eq!(radius("-int(-2.7)"), 2.0);
    assert_eq!(radius("mod(7, 3)"), 1.0);
    assert_eq!(radius("-mod(-7, 3)"), 1.0);
    assert_eq!(radius("mod(7.5, 2)"), 1.5);
    assert_eq!(radius("(y * 30).y"), 30.0);
    assert_eq!(radius("<4, 5, 6>.z"), 6.0);
    assert_eq!(radius("(rgb <0.1, 0.2, 0.3>).green"), 0.2);
    assert_eq!(num("let v = <1, 2, 3, 4>;", "v.t + v.x"), 5.0);
    assert_eq!(num("let uv = <0.25, 0.75>;", "uv.u + uv.v"), 1.0);
    assert_eq!(num("let xs = [<1, 2, 3>];", "xs[0].y"), 2.0);
    // A scene may bind the names itself.
    assert_eq!(num("let pi = 3;", "pi"), 3.0);
    assert_eq!(num("let x = 2;", "x * x"), 4.0);
    assert_eq!(radius("1 + clock_delta"), 1.0, "a still image's step is 0");
}

#[test]
fn povray_forms_that_ptsc_refuses_name_what_to_write() {
    assert_eq!(
        value("", "<1, 2>.z").unwrap_err(),
        codes::INDEX_OUT_OF_RANGE
    );
    assert_eq!(
        value("", "<1, 2, 3>.w").unwrap_err(),
        codes::UNKNOWN_COMPONENT
    );
    assert_eq!(
        value("", "(rgb 1).filter").unwrap_err(),
        codes::UNKNOWN_COMPONENT
    );
    assert_eq!(value("", "(2).x").unwrap_err(), codes::TYPE_MISMATCH);
    assert_eq!(value("", "mod(1, 0)").unwrap_err(), codes::DIVISION_BY_ZERO);
    let d = evaluate(super::MAX_WORK, "", "rgbft <1, 0.5, 0, 0.25, 0.25>").unwrap_err();
    assert_eq!(d.code, codes::FILTER_COLOR);
    let help = d.help.unwrap();
    assert!(
        help.contains("rgb <1, 0.5, 0>") && help.contains("transmission 0.5"),
        "{help}"
    );
    let d = evaluate(super::MAX_WORK, "", "vlength(<1, 0, 0>)").unwrap_err();
    assert!(d.help.unwrap().contains("length(v)"));
}

#[test]
fn a_string_written_out_has_the_bound_of_one_built() {
    // A literal of 5,000 bytes passed where `"" + it` was refused.
    let at = |n: usize| format!("\"{}\"", "a".repeat(n));
    let most = super::limits::MAX_STRING;
    assert!(value("", &at(most)).is_ok());
    assert_eq!(value("", &at(most + 1)), Err(codes::VALUE_TOO_LARGE.into()));
    assert_eq!(
        value("", &format!("{} + \"\"", at(most + 1))),
        Err(codes::VALUE_TOO_LARGE.into())
    );
}
