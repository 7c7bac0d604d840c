"""Gymnasium environments over lockstep (docs/fleet.md, "Reinforcement learning").

    env = contactsim.gym.ContactsimEnv(client, contactsim.gym.HoverTask())
    venv = contactsim.gym.FleetVectorEnv(contactsim.gym.HoverTask(), num_envs=2)

Needs gymnasium; FleetVectorEnv also ray.
"""
from .env import ContactsimEnv
from .tasks import ArmTask, HoverTask
from .vector import FleetVectorEnv

__all__ = ["ArmTask", "ContactsimEnv", "FleetVectorEnv", "HoverTask"]
