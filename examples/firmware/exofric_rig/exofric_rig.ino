// exofric_rig.ino -- reference firmware for the exofric serial line protocol (version 1).
//
// Hardware (adapt the pins and calibration constants below):
//   * pressure transducer, ratiometric 0.5-4.5 V for 0..1 MPa gauge, on analog pin A0;
//   * load cell through an HX711 (DOUT pin 3, SCK pin 2), calibrated in N;
//   * proportional pressure regulator with a 0-10 V (or 4-20 mA) input driven from PWM pin 9
//     through an RC filter and an amplifier (on a Teensy 3.x/4.x use the DAC pin instead);
//   * exhaust (vent) solenoid valve on digital pin 8 (HIGH = open to atmosphere).
// Protocol: see examples/serial-protocol.md. Units: MPa (gauge), N, ms.
//
// Safety: the tube is vented at power-up, on `V`, and when no command arrives within the
// watchdog time set by `W <ms>` (the host crashed or the cable was pulled).

#include <Arduino.h>

// ---- pins -----------------------------------------------------------------------------------
const int PIN_PRESSURE = A0;
const int PIN_HX_DOUT = 3;
const int PIN_HX_SCK = 2;
const int PIN_REGULATOR = 9;   // PWM (or DAC on a Teensy)
const int PIN_VENT = 8;

// ---- calibration ----------------------------------------------------------------------------
const float ADC_REF_V = 5.0;             // ADC reference in V
const float P_V_ZERO = 0.5;              // transducer output at 0 MPa, V
const float P_V_PER_MPA = 4.0;           // V per MPa (0.5..4.5 V = 0..1 MPa)
const float REG_MAX_MPA = 0.9;           // regulator full scale in MPa (PWM 255)
const float HX_N_PER_COUNT = 1.0e-4;     // load cell scale, N per HX711 count (calibrate!)
long hxOffset = 0;                       // tare, HX711 counts (measured at start-up)
const unsigned long STALE_MS = 250;      // no new HX711 sample for this long: `ERR stale`
                                         // (> 2 periods at 10 samples/s)

// ---- state ----------------------------------------------------------------------------------
unsigned long lastCommandMs = 0;
unsigned long watchdogMs = 0;            // 0 = off until the host sends W
unsigned long sampleMs = 0;              // time of the newest complete sample
float pressureMpa = 0.0;
float forceN = 0.0;
bool haveForce = false;
bool vented = true;
char line[48];
int lineLen = 0;

long hx711Read() {                       // one 24-bit conversion, gain 128 (channel A)
  long v = 0;
  for (int i = 0; i < 24; i++) {
    digitalWrite(PIN_HX_SCK, HIGH);
    delayMicroseconds(1);
    v = (v << 1) | digitalRead(PIN_HX_DOUT);
    digitalWrite(PIN_HX_SCK, LOW);
    delayMicroseconds(1);
  }
  digitalWrite(PIN_HX_SCK, HIGH);        // 25th pulse: gain 128 for the next conversion
  delayMicroseconds(1);
  digitalWrite(PIN_HX_SCK, LOW);
  if (v & 0x800000L) v |= 0xFF000000L;   // sign-extend
  return v;
}

void writeRegulator(float mpa) {
  if (mpa < 0.0) mpa = 0.0;
  if (mpa > REG_MAX_MPA) mpa = REG_MAX_MPA;
  analogWrite(PIN_REGULATOR, (int)(255.0 * mpa / REG_MAX_MPA + 0.5));
}

void vent() {
  writeRegulator(0.0);
  digitalWrite(PIN_VENT, HIGH);
  vented = true;
}

void sampleSensors() {
  // The HX711 delivers 10 or 80 samples/s: take a new force value only when one is ready, and
  // advance sampleMs only then, so the host can tell a frozen load cell from a steady one.
  if (digitalRead(PIN_HX_DOUT) == LOW) {
    forceN = (hx711Read() - hxOffset) * HX_N_PER_COUNT;
    float volts = analogRead(PIN_PRESSURE) * ADC_REF_V / 1023.0;
    pressureMpa = (volts - P_V_ZERO) / P_V_PER_MPA;
    sampleMs = millis();
    haveForce = true;
  }
}

void answer(const char *cmd) {
  lastCommandMs = millis();
  if (strcmp(cmd, "?") == 0) {
    Serial.println("EXOFRIC-RIG 1 exofric_rig 1.0");
  } else if (strcmp(cmd, "R") == 0) {
    if (!haveForce || millis() - sampleMs > STALE_MS) {
      Serial.println("ERR stale");       // never sampled, or the load cell stopped
      return;
    }
    Serial.print("D ");
    Serial.print(sampleMs);
    Serial.print(' ');
    Serial.print(pressureMpa, 6);
    Serial.print(' ');
    Serial.println(forceN, 4);
  } else if (cmd[0] == 'S' && cmd[1] == ' ') {
    char *end;
    float p = strtod(cmd + 2, &end);
    if (end == cmd + 2 || *end != '\0' || p != p) {   // not a number (or NaN): refuse
      Serial.println("ERR bad set-point");
      return;
    }
    if (p < 0.0 || p > REG_MAX_MPA) {
      Serial.println("ERR set-point out of range");
      return;
    }
    digitalWrite(PIN_VENT, LOW);
    vented = false;
    writeRegulator(p);
    Serial.println("OK");
  } else if (strcmp(cmd, "V") == 0) {
    vent();
    Serial.println("OK");
  } else if (cmd[0] == 'W' && cmd[1] == ' ') {
    char *end;
    unsigned long ms = strtoul(cmd + 2, &end, 10);
    if (end == cmd + 2 || *end != '\0') {
      Serial.println("ERR bad watchdog time");
      return;
    }
    watchdogMs = ms;
    Serial.println("OK");
  } else {
    Serial.println("ERR unknown command");
  }
}

void setup() {
  pinMode(PIN_VENT, OUTPUT);
  pinMode(PIN_REGULATOR, OUTPUT);
  pinMode(PIN_HX_SCK, OUTPUT);
  pinMode(PIN_HX_DOUT, INPUT);
  vent();                                // power-up: tube at atmosphere
  Serial.begin(115200);
  long sum = 0;                          // tare the load cell (unloaded at start-up)
  for (int i = 0; i < 8; i++) {
    while (digitalRead(PIN_HX_DOUT) == HIGH) {}
    sum += hx711Read();
  }
  hxOffset = sum / 8;
}

void loop() {
  sampleSensors();
  while (Serial.available() > 0) {
    char c = (char)Serial.read();
    if (c == '\r') continue;
    if (c == '\n') {
      line[lineLen] = '\0';
      answer(line);
      lineLen = 0;
    } else if (lineLen < (int)sizeof(line) - 1) {
      line[lineLen++] = c;
    }
  }
  if (watchdogMs > 0 && !vented && millis() - lastCommandMs > watchdogMs) {
    vent();                              // the host went silent
  }
}
