//! `env play`: a person plays a task in the terminal; every step is recorded as JSON lines.
//!
//! Keys: arrows or WASD move, space or E interact, `.` wait, digits 0–5 are raw action
//! codes, q quits. With a terminal on stdin keys are read one by one (raw mode);
//! otherwise characters are read from stdin (scripted sessions, tests).

use super::TaskArgs;
use anyhow::{Context, Result};
use chronocooked_env::{Action, ChronoEnv, render, trace::TraceLine};
use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, read};
use crossterm::terminal::{disable_raw_mode, enable_raw_mode};
use std::fs::OpenOptions;
use std::io::{BufWriter, IsTerminal, Read, Write};
use std::path::Path;

/// A key press mapped to what the player wants.
enum Input {
    Act(Action),
    Quit,
    Ignore,
}

fn map_char(c: char) -> Input {
    match c.to_ascii_lowercase() {
        'w' | 'k' => Input::Act(Action::Up),
        's' | 'j' => Input::Act(Action::Down),
        'd' | 'l' => Input::Act(Action::Right),
        'a' | 'h' => Input::Act(Action::Left),
        'e' | ' ' => Input::Act(Action::Interact),
        '.' => Input::Act(Action::Wait),
        'q' => Input::Quit,
        d @ '0'..='5' => Input::Act(Action::ALL[d as usize - '0' as usize]),
        _ => Input::Ignore,
    }
}

fn map_key(k: KeyEvent) -> Input {
    if k.kind != KeyEventKind::Press {
        return Input::Ignore;
    }
    match k.code {
        KeyCode::Up => Input::Act(Action::Up),
        KeyCode::Down => Input::Act(Action::Down),
        KeyCode::Left => Input::Act(Action::Left),
        KeyCode::Right => Input::Act(Action::Right),
        KeyCode::Enter => Input::Act(Action::Interact),
        KeyCode::Esc => Input::Quit,
        KeyCode::Char('c') if k.modifiers.contains(KeyModifiers::CONTROL) => Input::Quit,
        KeyCode::Char(c) => map_char(c),
        _ => Input::Ignore,
    }
}

/// Source of key presses: raw terminal or plain stdin characters.
struct Keys {
    tty: bool,
    stdin: std::io::Stdin,
}

impl Keys {
    fn next(&mut self) -> Result<Input> {
        if self.tty {
            loop {
                if let Event::Key(k) = read()? {
                    return Ok(map_key(k));
                }
            }
        }
        let mut byte = [0u8; 1];
        match self.stdin.read(&mut byte)? {
            0 => Ok(Input::Quit),
            _ => Ok(map_char(byte[0] as char)),
        }
    }
}

/// Restores the terminal even on error.
struct RawGuard(bool);

impl Drop for RawGuard {
    fn drop(&mut self) {
        if self.0 {
            let _ = disable_raw_mode();
        }
    }
}

fn show(env: &ChronoEnv, episode: u32, steps: u32, total: f64, message: &str, tty: bool) {
    let nl = if tty { "\r\n" } else { "\n" };
    let mut text = String::new();
    if tty {
        text.push_str("\x1b[2J\x1b[H");
    }
    text.push_str(&format!(
        "{} — episode {episode}, step {steps}, return {total:.2}{nl}{nl}",
        env.config().id
    ));
    let grid = render::ascii(env.layout(), env.family(), env.obs_codes());
    text.push_str(&grid.replace('\n', nl));
    text.push_str(&format!(
        "{nl}arrows/WASD move · space/E interact · . wait · q quit{nl}{message}{nl}"
    ));
    print!("{text}");
    let _ = std::io::stdout().flush();
}

/// Runs an interactive session, appending every line to `record`.
pub fn run(args: &TaskArgs, record: &Path, episodes: u32) -> Result<()> {
    let (mut env, options) = args.build()?;
    let file = OpenOptions::new()
        .create(true)
        .append(true)
        .open(record)
        .with_context(|| format!("cannot open recording file {}", record.display()))?;
    let mut out = BufWriter::new(file);
    let tty = std::io::stdin().is_terminal() && std::io::stdout().is_terminal();
    let _guard = RawGuard(tty && enable_raw_mode().is_ok());
    let mut keys = Keys {
        tty,
        stdin: std::io::stdin(),
    };
    let mut episode = 0;
    'episodes: while episodes == 0 || episode < episodes {
        let seed = if episode == 0 { Some(args.seed) } else { None };
        let info = env.reset(seed, &options)?;
        let line = TraceLine::reset(&env, info).with_reset_key(seed, options);
        writeln!(out, "{}", line.to_json())?;
        out.flush()?;
        let (mut steps, mut total) = (0u32, 0.0f64);
        show(&env, episode + 1, steps, total, "", tty);
        while !env.is_done() {
            let action = match keys.next()? {
                Input::Act(a) => a,
                Input::Quit => break 'episodes,
                Input::Ignore => continue,
            };
            let t = env.step(action)?;
            steps += 1;
            total += t.reward as f64;
            writeln!(out, "{}", TraceLine::step(&env, action, &t).to_json())?;
            out.flush()?;
            let message = if t.terminated {
                format!("episode over: return {total:.2}")
            } else if t.truncated {
                "time limit reached".to_string()
            } else {
                String::new()
            };
            show(&env, episode + 1, steps, total, &message, tty);
        }
        episode += 1;
    }
    drop(_guard);
    println!("recorded {episode} episode(s) to {}", record.display());
    Ok(())
}
